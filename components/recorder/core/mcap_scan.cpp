#include "recorder/core/mcap_scan.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <set>

#include "common/core/byte_io.hpp"
#include "common/core/crc32.hpp"
#include "common/core/io_error.hpp"
#include "recorder/core/compression.hpp"

namespace ltm::recorder {

FileSource::FileSource(const std::string& path) : path_(path) {
    fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd_ < 0) throw common::IoError(path, std::string("cannot open: ") + std::strerror(errno));
    struct stat st {};
    if (::fstat(fd_, &st) != 0 || !S_ISREG(st.st_mode)) {
        ::close(fd_);
        throw common::IoError(path, "not a regular file");
    }
    size_ = static_cast<std::uint64_t>(st.st_size);
}

FileSource::~FileSource() {
    if (fd_ >= 0) ::close(fd_);
}

bool FileSource::read(std::uint64_t offset, std::size_t n, std::vector<std::uint8_t>& out) const {
    if (offset > size_ || n > size_ - offset) return false;
    out.resize(n);
    std::size_t done = 0;
    while (done < n) {
        const ssize_t got =
            ::pread(fd_, out.data() + done, n - done, static_cast<off_t>(offset + done));
        if (got < 0 && errno == EINTR) continue;
        if (got <= 0) return false;
        done += static_cast<std::size_t>(got);
    }
    return true;
}

std::string describe_op(std::uint8_t op) {
    const std::string name = op_name(op);
    if (name != "unknown") return name;
    char buf[16];
    std::snprintf(buf, sizeof buf, "opcode 0x%02x", op);
    return buf;
}

void decode_chunk(const std::uint8_t* content, std::size_t size, bool check_crc, ChunkRecord& chunk,
                  std::vector<std::uint8_t>& records) {
    parse_chunk(content, size, chunk);
    const std::uint64_t at = static_cast<std::uint64_t>(chunk.records - content);
    try {
        decompress(chunk.compression, chunk.records, static_cast<std::size_t>(chunk.records_size),
                   chunk.uncompressed_size, records);
    } catch (const common::FormatError& e) {
        throw common::FormatError("Chunk record", "records", at,
                                  std::string("cannot decompress (") + e.what() + ")");
    }
    if (check_crc && chunk.uncompressed_crc != 0) {
        const std::uint32_t got = common::crc32(records.data(), records.size());
        if (got != chunk.uncompressed_crc) {
            throw common::FormatError("Chunk record", "records", at,
                                      "CRC mismatch (stored " +
                                          common::hex32(chunk.uncompressed_crc) + ", computed " +
                                          common::hex32(got) + ")");
        }
    }
}

void for_each_record(
    const std::uint8_t* p, std::size_t n,
    const std::function<void(std::uint8_t, const std::uint8_t*, std::size_t, std::size_t)>& fn) {
    std::size_t pos = 0;
    while (pos < n) {
        if (n - pos < kRecordPrefix) {
            throw common::FormatError("records", "record header", pos,
                                      "partial (" + std::to_string(n - pos) + " of " +
                                          std::to_string(kRecordPrefix) + " bytes)");
        }
        const std::uint8_t op = p[pos];
        std::uint64_t len = 0;
        std::memcpy(&len, p + pos + 1, 8);
        if (len > n - pos - kRecordPrefix) {
            throw common::FormatError("records", describe_op(op) + " record", pos,
                                      "claims " + std::to_string(len) + " bytes, only " +
                                          std::to_string(n - pos - kRecordPrefix) + " remain");
        }
        fn(op, p + pos + kRecordPrefix, static_cast<std::size_t>(len), pos);
        pos += kRecordPrefix + static_cast<std::size_t>(len);
    }
}

namespace {

using IndexEntries = std::vector<std::pair<std::uint64_t, std::uint64_t>>;

class Scanner {
  public:
    Scanner(const FileSource& file, const ScanOptions& options) : file_(file), options_(options) {}

    ScanResult run() {
        crc_ = common::crc32_init();
        std::vector<std::uint8_t> magic;
        file_.read(0, kMagicSize, magic);  // the reader checked it already
        crc_ = common::crc32_update(crc_, magic.data(), magic.size());
        std::uint64_t pos = kMagicSize;
        r_.readable_end = pos;
        bool first = true;
        while (true) {
            if (pos == file_.size()) {
                problem("file ends at byte " + std::to_string(pos) + " without DataEnd or Footer");
                break;
            }
            if (file_.size() - pos < kRecordPrefix) {
                problem("partial record header at byte " + std::to_string(pos));
                break;
            }
            file_.read(pos, kRecordPrefix, prefix_);
            const std::uint8_t op = prefix_[0];
            std::uint64_t len = 0;
            std::memcpy(&len, prefix_.data() + 1, 8);
            const std::uint64_t left = file_.size() - pos - kRecordPrefix;
            if (len > left) {
                problem(describe_op(op) + " record at byte " + std::to_string(pos) + " needs " +
                        std::to_string(len) + " bytes, only " + std::to_string(left) + " remain");
                break;
            }
            if (first && op != static_cast<std::uint8_t>(Op::kHeader)) {
                problem("first record at byte 8 is " + describe_op(op) + ", not Header");
                break;
            }
            if (op == static_cast<std::uint8_t>(Op::kFooter)) {
                r_.footer_found = true;
                break;
            }
            if (!file_.read(pos + kRecordPrefix, static_cast<std::size_t>(len), content_)) {
                problem("read error at byte " + std::to_string(pos));
                break;
            }
            if (op == static_cast<std::uint8_t>(Op::kDataEnd)) {
                data_end(pos);
                break;
            }
            crc_ = common::crc32_update(crc_, prefix_.data(), prefix_.size());
            crc_ = common::crc32_update(crc_, content_.data(), content_.size());
            if (!record(op, pos, len, first)) break;
            first = false;
            pos += kRecordPrefix + len;
            r_.readable_end = pos;
        }
        finish_chunk_checks();
        r_.statistics.schema_count = static_cast<std::uint16_t>(r_.schemas.size());
        r_.statistics.channel_count = static_cast<std::uint32_t>(r_.channels.size());
        return std::move(r_);
    }

  private:
    void problem(const std::string& p) { r_.problems.push_back(p); }

    void data_end(std::uint64_t pos) {
        r_.data_end_found = true;
        r_.data_end_offset = pos;
        std::uint32_t stored = 0;
        if (content_.size() >= 4) std::memcpy(&stored, content_.data(), 4);
        const std::uint32_t computed = common::crc32_final(crc_);
        if (options_.check_crcs && stored != 0 && stored != computed) {
            char buf[160];
            std::snprintf(buf, sizeof buf,
                          "data section CRC mismatch (stored %08x, computed %08x) in DataEnd at "
                          "byte %llu",
                          stored, computed, static_cast<unsigned long long>(pos));
            problem(buf);
        }
    }

    // Returns false when scanning must stop.
    bool record(std::uint8_t op, std::uint64_t pos, std::uint64_t len, bool first) {
        const std::uint8_t* c = content_.data();
        const std::size_t n = static_cast<std::size_t>(len);
        const std::string at = " at byte " + std::to_string(pos);
        switch (static_cast<Op>(op)) {
            case Op::kHeader:
                if (!first) {
                    problem("repeated Header" + at);
                    return false;
                }
                try {
                    parse_header(c, n, r_.header);
                } catch (const common::FormatError& e) {
                    problem("malformed Header" + at + " (" + describe(e) + ")");
                    return false;
                }
                return true;
            case Op::kSchema:
                schema(c, n, at);
                return true;
            case Op::kChannel:
                channel(c, n, at);
                return true;
            case Op::kMessage:
                loose_message(c, n, pos, at);
                return true;
            case Op::kChunk:
                chunk(c, n, pos, at);
                return true;
            case Op::kMessageIndex:
                message_index(c, n, at);
                return true;
            default:
                return true;  // attachments, metadata, unknown: skipped
        }
    }

    void schema(const std::uint8_t* c, std::size_t n, const std::string& at) {
        Schema s;
        try {
            parse_schema(c, n, s);
        } catch (const common::FormatError& e) {
            problem("malformed Schema record" + at + " (" + describe(e) + ")");
            return;
        }
        if (s.id == 0) {
            problem("malformed Schema record" + at + " (id 0)");
            return;
        }
        const auto [it, inserted] = r_.schemas.emplace(s.id, s);
        if (!inserted && !(it->second == s)) {
            problem("Schema " + std::to_string(s.id) + at + " differs from an earlier one");
        }
    }

    void channel(const std::uint8_t* c, std::size_t n, const std::string& at) {
        Channel ch;
        try {
            parse_channel(c, n, ch);
        } catch (const common::FormatError& e) {
            problem("malformed Channel record" + at + " (" + describe(e) + ")");
            return;
        }
        const auto [it, inserted] = r_.channels.emplace(ch.id, ch);
        if (!inserted && !(it->second == ch)) {
            problem("Channel " + std::to_string(ch.id) + at + " differs from an earlier one");
        }
    }

    // Counts a message; returns false if it cannot be used.
    bool count(const MessageRecord& m, const std::string& at) {
        if (!r_.channels.count(m.channel_id)) {
            problem("Message on unknown channel " + std::to_string(m.channel_id) + at);
            return false;
        }
        Statistics& s = r_.statistics;
        if (s.message_count == 0) {
            s.message_start_time = s.message_end_time = m.log_time;
        } else {
            s.message_start_time = std::min(s.message_start_time, m.log_time);
            s.message_end_time = std::max(s.message_end_time, m.log_time);
        }
        ++s.message_count;
        ++s.channel_message_counts[m.channel_id];
        return true;
    }

    void loose_message(const std::uint8_t* c, std::size_t n, std::uint64_t pos,
                       const std::string& at) {
        MessageRecord m;
        try {
            parse_message(c, n, m);
        } catch (const common::FormatError& e) {
            problem("malformed Message record" + at + " (" + describe(e) + ")");
            return;
        }
        if (!count(m, at)) return;
        const std::uint64_t rec_len = kRecordPrefix + n;
        if (!r_.chunks.empty() && r_.chunks.back().loose_messages &&
            r_.chunks.back().offset + r_.chunks.back().length == pos) {
            ChunkInfo& run = r_.chunks.back();
            run.length += rec_len;
            run.compressed_size = run.uncompressed_size = run.length;
            run.start_time = std::min(run.start_time, m.log_time);
            run.end_time = std::max(run.end_time, m.log_time);
            ++run.messages;
            return;
        }
        ChunkInfo run;
        run.offset = pos;
        run.length = run.compressed_size = run.uncompressed_size = rec_len;
        run.start_time = run.end_time = m.log_time;
        run.messages = 1;
        run.loose_messages = true;
        r_.chunks.push_back(run);
    }

    void chunk(const std::uint8_t* c, std::size_t n, std::uint64_t pos, const std::string& at) {
        finish_chunk_checks();
        ChunkRecord rec;
        try {
            decode_chunk(c, n, options_.check_crcs, rec, records_);
        } catch (const common::FormatError& e) {
            problem("Chunk" + at + ": " + describe(e) + "; skipped");
            r_.bad_chunks.push_back(pos);
            skipping_indexes_ = true;  // its MessageIndex records follow
            return;
        }
        skipping_indexes_ = false;
        ChunkInfo info;
        info.offset = pos;
        info.length = kRecordPrefix + n;
        info.start_time = rec.message_start_time;
        info.end_time = rec.message_end_time;
        info.compression = rec.compression;
        info.compressed_size = rec.records_size;
        info.uncompressed_size = rec.uncompressed_size;
        std::map<std::uint16_t, IndexEntries> expected;
        std::string bad_inner;  // the first malformed record inside
        try {
            for_each_record(
                records_.data(), records_.size(),
                [&](std::uint8_t op, const std::uint8_t* rc, std::size_t rn, std::size_t off) {
                    const std::string inner = at + " +" + std::to_string(off);
                    if (op == static_cast<std::uint8_t>(Op::kSchema))
                        schema(rc, rn, inner);
                    else if (op == static_cast<std::uint8_t>(Op::kChannel))
                        channel(rc, rn, inner);
                    else if (op == static_cast<std::uint8_t>(Op::kMessage)) {
                        MessageRecord m;
                        try {
                            parse_message(rc, rn, m);
                        } catch (const common::FormatError& e) {
                            if (bad_inner.empty()) {
                                bad_inner =
                                    "Message at +" + std::to_string(off) + ": " + describe(e);
                            }
                            return;
                        }
                        if (count(m, " in Chunk" + inner)) {
                            ++info.messages;
                            expected[m.channel_id].emplace_back(m.log_time, off);
                        }
                    }
                });
        } catch (const common::FormatError& e) {
            if (bad_inner.empty()) bad_inner = describe(e);
        }
        if (!bad_inner.empty())
            problem("Chunk" + at + ": malformed records inside (" + bad_inner + ")");
        r_.chunks.push_back(info);
        ++r_.statistics.chunk_count;
        if (options_.check_message_indexes) {
            for (auto& [ch, e] : expected) std::sort(e.begin(), e.end());
            expected_indexes_ = std::move(expected);
            expected_chunk_at_ = pos;
            checking_indexes_ = true;
        }
    }

    void message_index(const std::uint8_t* c, std::size_t n, const std::string& at) {
        if (!options_.check_message_indexes || skipping_indexes_) return;
        std::uint16_t ch = 0;
        IndexEntries entries;
        try {
            parse_message_index(c, n, ch, entries);
        } catch (const common::FormatError& e) {
            problem("malformed MessageIndex" + at + " (" + describe(e) + ")");
            return;
        }
        if (!checking_indexes_) {
            problem("MessageIndex" + at + " does not follow a chunk");
            return;
        }
        std::sort(entries.begin(), entries.end());
        const auto it = expected_indexes_.find(ch);
        if (it == expected_indexes_.end() || it->second != entries) {
            problem("MessageIndex" + at + " for channel " + std::to_string(ch) +
                    " does not match the chunk at byte " + std::to_string(expected_chunk_at_));
        }
        if (it != expected_indexes_.end()) expected_indexes_.erase(it);
    }

    // Every channel of the previous chunk must have had its MessageIndex.
    void finish_chunk_checks() {
        if (checking_indexes_ && !expected_indexes_.empty()) {
            problem("chunk at byte " + std::to_string(expected_chunk_at_) +
                    " lacks the MessageIndex of " + std::to_string(expected_indexes_.size()) +
                    " channel(s)");
        }
        expected_indexes_.clear();
        checking_indexes_ = false;
    }

    const FileSource& file_;
    ScanOptions options_;
    ScanResult r_;
    std::uint32_t crc_ = 0;
    std::vector<std::uint8_t> prefix_, content_, records_;
    std::map<std::uint16_t, IndexEntries> expected_indexes_;
    std::uint64_t expected_chunk_at_ = 0;
    bool checking_indexes_ = false;
    bool skipping_indexes_ = false;
};

}  // namespace

ScanResult scan_mcap(const FileSource& file, const ScanOptions& options) {
    return Scanner(file, options).run();
}

}  // namespace ltm::recorder
