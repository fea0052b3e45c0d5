#include "recorder/core/mcap_reader.hpp"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <set>

#include "common/core/crc32.hpp"
#include "common/core/io_error.hpp"

namespace ltm::recorder {
namespace {

std::string hex_prefix(const std::vector<std::uint8_t>& b) {
    std::string s;
    char buf[4];
    for (std::size_t i = 0; i < b.size() && i < 8; ++i) {
        std::snprintf(buf, sizeof buf, "%02x", b[i]);
        s += (i ? " " : "") + std::string(buf);
    }
    return s;
}

std::string at(std::uint64_t offset) { return " at byte " + std::to_string(offset); }

}  // namespace

McapReader::McapReader(const std::string& path) : file_(std::make_unique<FileSource>(path)) {
    const std::uint64_t size = file_->size();
    std::vector<std::uint8_t> head;
    if (size < kMagicSize || !file_->read(0, kMagicSize, head)) {
        throw common::IoError(path, "not an MCAP file: only " + std::to_string(size) + " bytes");
    }
    if (std::memcmp(head.data(), kMcapMagic, 5) != 0) {
        throw common::IoError(
            path, "not an MCAP file: bad magic at byte 0 (found " + hex_prefix(head) + ")");
    }
    if (std::memcmp(head.data(), kMcapMagic, kMagicSize) != 0) {
        throw common::IoError(path, "unsupported MCAP version byte '" +
                                        std::string(1, static_cast<char>(head[5])) +
                                        "' at byte 5 (this reader knows major version 0)");
    }
    std::vector<std::uint8_t> prefix;
    if (file_->read(kMagicSize, kRecordPrefix, prefix) &&
        prefix[0] != static_cast<std::uint8_t>(Op::kHeader)) {
        throw common::IoError(path, "not an MCAP file: record at byte 8 is " +
                                        describe_op(prefix[0]) + ", not Header");
    }
    if (open_summary()) return;
    ScanResult scan = scan_mcap(*file_, ScanOptions{});
    if (cut_short_) {
        // One line: where the file was cut and what is still readable.
        std::size_t chunks = 0;
        for (const auto& c : scan.chunks) chunks += c.loose_messages ? 0 : 1;
        std::string line =
            "cut short (no Footer at the end of its " + std::to_string(size) + " bytes)";
        if (!scan.problems.empty()) line += ": " + scan.problems.front();
        line += "; " + std::to_string(scan.statistics.message_count) + " messages in " +
                std::to_string(chunks) + " complete chunks are readable, recover() completes it";
        if (scan.problems.empty())
            scan.problems.push_back(line);
        else
            scan.problems.front() = line;
    }
    adopt_scan(std::move(scan));
}

McapReader::~McapReader() = default;

void McapReader::report(const std::string& problem) { problems_.push_back(problem); }

MessageCursor McapReader::messages(const ReadOptions& options) {
    return MessageCursor(*this, options);
}

void McapReader::adopt_scan(ScanResult&& scan) {
    header_ = std::move(scan.header);
    schemas_ = std::move(scan.schemas);
    channels_ = std::move(scan.channels);
    chunks_ = std::move(scan.chunks);
    statistics_ = std::move(scan.statistics);
    for (auto& p : scan.problems) problems_.push_back(std::move(p));
}

bool McapReader::open_summary() {
    const std::uint64_t size = file_->size();
    const std::uint64_t tail_size = kFooterRecord + kMagicSize;
    std::vector<std::uint8_t> tail;
    if (size < kMagicSize + kRecordPrefix + 8 + tail_size ||
        !file_->read(size - tail_size, tail_size, tail) ||
        std::memcmp(tail.data() + kFooterRecord, kMcapMagic, kMagicSize) != 0) {
        cut_short_ = true;  // the scan says where it was cut
        return false;
    }
    const std::uint64_t footer_at = size - tail_size;
    std::uint64_t len = 0;
    std::memcpy(&len, tail.data() + 1, 8);
    if (tail[0] != static_cast<std::uint8_t>(Op::kFooter) || len != kFooterContent) {
        problems_.push_back("malformed Footer" + at(footer_at) + "; reading by linear scan");
        return false;
    }
    parse_footer(tail.data() + kRecordPrefix, kFooterContent, footer_);  // its size was checked
    complete_ = true;
    if (footer_.summary_start == 0) return false;  // complete, but without a summary: scan
    if (footer_.summary_start < kMagicSize + kRecordPrefix || footer_.summary_start > footer_at) {
        problems_.push_back("Footer" + at(footer_at) + " puts the summary at byte " +
                            std::to_string(footer_.summary_start) +
                            ", outside the file; reading by linear scan");
        complete_ = false;
        return false;
    }
    std::vector<std::uint8_t> summary;
    file_->read(footer_.summary_start, footer_at - footer_.summary_start, summary);
    if (footer_.summary_crc != 0) {
        std::uint32_t crc =
            common::crc32_update(common::crc32_init(), summary.data(), summary.size());
        crc = common::crc32_final(common::crc32_update(crc, tail.data(), kRecordPrefix + 16));
        if (crc != footer_.summary_crc) {
            char buf[160];
            std::snprintf(buf, sizeof buf,
                          "summary CRC mismatch (stored %08x, computed %08x) for the summary at "
                          "byte %llu; reading by linear scan",
                          footer_.summary_crc, crc,
                          static_cast<unsigned long long>(footer_.summary_start));
            problems_.push_back(buf);
            complete_ = false;
            return false;
        }
    }
    bool has_statistics = false, bad = false;
    std::vector<ChunkInfo> chunks;
    const auto malformed = [&](std::uint8_t op, std::size_t off, const std::string& why) {
        if (bad) return;
        bad = true;
        problems_.push_back("malformed " + describe_op(op) + " record in the summary" +
                            at(footer_.summary_start + off) + " (" + why +
                            "); reading by linear scan");
    };
    try {
        for_each_record(
            summary.data(), summary.size(),
            [&](std::uint8_t op, const std::uint8_t* c, std::size_t n, std::size_t off) {
                try {
                    switch (static_cast<Op>(op)) {
                        case Op::kSchema: {
                            Schema s;
                            parse_schema(c, n, s);
                            if (s.id != 0) schemas_[s.id] = s;
                            break;
                        }
                        case Op::kChannel: {
                            Channel ch;
                            parse_channel(c, n, ch);
                            channels_[ch.id] = ch;
                            break;
                        }
                        case Op::kStatistics:
                            parse_statistics(c, n, statistics_);
                            has_statistics = true;
                            break;
                        case Op::kChunkIndex: {
                            ChunkIndex ci;
                            parse_chunk_index(c, n, ci);
                            if (ci.chunk_start_offset > footer_.summary_start ||
                                ci.chunk_length > footer_.summary_start - ci.chunk_start_offset) {
                                malformed(op, off, "the chunk lies beyond the data section");
                                break;
                            }
                            ChunkInfo info;
                            info.offset = ci.chunk_start_offset;
                            info.length = ci.chunk_length;
                            info.start_time = ci.message_start_time;
                            info.end_time = ci.message_end_time;
                            info.compression = ci.compression;
                            info.compressed_size = ci.compressed_size;
                            info.uncompressed_size = ci.uncompressed_size;
                            info.message_index_offsets = ci.message_index_offsets;
                            info.message_index_length = ci.message_index_length;
                            chunks.push_back(std::move(info));
                            break;
                        }
                        default:
                            break;
                    }
                } catch (const common::FormatError& e) {
                    malformed(op, off, describe(e));
                }
            });
    } catch (const common::FormatError& e) {
        if (!bad) {
            bad = true;
            problems_.push_back("summary at byte " + std::to_string(footer_.summary_start) + ": " +
                                describe(e) + "; reading by linear scan");
        }
    }
    if (bad) {
        complete_ = false;
        schemas_.clear();
        channels_.clear();
        return false;
    }
    // Without statistics, or with messages outside chunks, the scan is what counts them.
    if (!has_statistics || (statistics_.message_count > 0 && chunks.empty())) {
        schemas_.clear();
        channels_.clear();
        statistics_ = Statistics{};
        return false;
    }
    std::vector<std::uint8_t> prefix;
    std::uint64_t hlen = 0;
    if (file_->read(kMagicSize, kRecordPrefix, prefix)) std::memcpy(&hlen, prefix.data() + 1, 8);
    std::vector<std::uint8_t> hbytes;
    try {
        if (hlen > footer_.summary_start || !file_->read(kMagicSize + kRecordPrefix, hlen, hbytes))
            throw common::FormatError("Header record", "beyond the summary or the file");
        parse_header(hbytes.data(), hbytes.size(), header_);
    } catch (const common::FormatError& e) {
        problems_.push_back("malformed Header at byte 8 (" + describe(e) + ")");
    }
    std::sort(chunks.begin(), chunks.end(),
              [](const ChunkInfo& a, const ChunkInfo& b) { return a.offset < b.offset; });
    chunks_ = std::move(chunks);
    indexed_ = true;
    return true;
}

VerifyReport McapReader::verify() const {
    VerifyReport rep;
    ScanOptions options;
    options.check_message_indexes = true;
    ScanResult s = scan_mcap(*file_, options);
    rep.problems = s.problems;
    auto problem = [&](const std::string& p) { rep.problems.push_back(p); };
    if (!complete_) {
        problem(problems_.empty() ? std::string("no intact Footer") : problems_.front());
    }
    if (!s.data_end_found && s.problems.empty()) problem("no DataEnd record before the Footer");
    if (indexed_) {
        std::map<std::uint64_t, const ChunkInfo*> data_chunks;
        for (const auto& c : s.chunks) {
            if (!c.loose_messages) data_chunks[c.offset] = &c;
        }
        const std::set<std::uint64_t> bad(s.bad_chunks.begin(), s.bad_chunks.end());
        if (data_chunks.size() + bad.size() != chunks_.size()) {
            problem("summary indexes " + std::to_string(chunks_.size()) + " chunks, data holds " +
                    std::to_string(data_chunks.size() + bad.size()));
        }
        for (const ChunkInfo& a : chunks_) {
            if (bad.count(a.offset)) continue;  // reported by the scan
            const auto found = data_chunks.find(a.offset);
            if (found == data_chunks.end()) {
                problem("ChunkIndex points at byte " + std::to_string(a.offset) +
                        ", where the data holds no chunk");
                continue;
            }
            const ChunkInfo& b = *found->second;
            if (a.length != b.length || a.start_time != b.start_time || a.end_time != b.end_time ||
                a.compression != b.compression || a.compressed_size != b.compressed_size ||
                a.uncompressed_size != b.uncompressed_size) {
                problem("ChunkIndex of the chunk at byte " + std::to_string(a.offset) +
                        " does not match the chunk");
            }
            std::uint64_t total = 0;
            for (const auto& [ch, off] : a.message_index_offsets) {
                std::vector<std::uint8_t> p;
                std::uint16_t got = 0;
                std::uint64_t len = 0;
                if (file_->read(off, kRecordPrefix + 2, p)) {
                    std::memcpy(&len, p.data() + 1, 8);
                    std::memcpy(&got, p.data() + kRecordPrefix, 2);
                }
                total += kRecordPrefix + len;
                if (p.empty() || p[0] != static_cast<std::uint8_t>(Op::kMessageIndex) ||
                    got != ch) {
                    problem("ChunkIndex of the chunk at byte " + std::to_string(a.offset) +
                            " points at byte " + std::to_string(off) +
                            " for the MessageIndex of channel " + std::to_string(ch) +
                            ", which is not there");
                }
            }
            if (!a.message_index_offsets.empty() && total != a.message_index_length) {
                problem("ChunkIndex of the chunk at byte " + std::to_string(a.offset) +
                        ": message_index_length does not match its MessageIndex records");
            }
        }
        const Statistics& x = statistics_;
        const Statistics& y = s.statistics;
        if (bad.empty() && (x.message_count != y.message_count || x.chunk_count != y.chunk_count ||
                            x.channel_message_counts != y.channel_message_counts ||
                            (y.message_count > 0 && (x.message_start_time != y.message_start_time ||
                                                     x.message_end_time != y.message_end_time)))) {
            problem("summary Statistics (" + std::to_string(x.message_count) + " messages, " +
                    std::to_string(x.chunk_count) + " chunks) do not match the data (" +
                    std::to_string(y.message_count) + " messages, " +
                    std::to_string(y.chunk_count) + " chunks)");
        }
        for (const auto& [id, ch] : s.channels) {
            const auto it = channels_.find(id);
            if (it == channels_.end() || !(it->second == ch)) {
                problem("Channel " + std::to_string(id) +
                        " of the data is missing or different "
                        "in the summary");
            }
        }
        for (const auto& [id, sc] : s.schemas) {
            const auto it = schemas_.find(id);
            if (it == schemas_.end() || !(it->second == sc)) {
                problem("Schema " + std::to_string(id) +
                        " of the data is missing or different "
                        "in the summary");
            }
        }
    }
    rep.messages = s.statistics.message_count;
    rep.chunks = s.statistics.chunk_count;
    rep.ok = rep.problems.empty();
    return rep;
}

}  // namespace ltm::recorder
