#include "link/core/link_journal.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "common/core/crc32.hpp"
#include "common/core/file_io.hpp"
#include "common/core/io_error.hpp"

namespace ltm::link {
namespace {

namespace fs = std::filesystem;
constexpr std::uint32_t kMagic = 0x4A4D544C;  // "LTMJ"
constexpr std::size_t kHead = 12;             // magic, body length, CRC
constexpr std::size_t kFixed = 8 + 8 + 2 + 2;
constexpr std::uint32_t kMaxBody = 1u << 30;

template <class T>
void put(std::vector<std::uint8_t>& out, T v) {
    const auto* b = reinterpret_cast<const std::uint8_t*>(&v);
    out.insert(out.end(), b, b + sizeof(T));
}
template <class T>
T get(const std::uint8_t* p) {
    T v;
    std::memcpy(&v, p, sizeof(T));
    return v;
}

std::string segment_name(std::uint64_t first_seq) {
    char name[40];
    std::snprintf(name, sizeof name, "seg-%020llu.ltmj",
                  static_cast<unsigned long long>(first_seq));
    return name;
}

std::string sys_error() { return std::strerror(errno); }

// Parses a record body; false when it does not hold one.
bool parse_body(const std::uint8_t* b, std::size_t n, JournalRecord& r) {
    if (n < kFixed) return false;
    r.seq = get<std::uint64_t>(b);
    r.stamp_ns = get<std::int64_t>(b + 8);
    const std::size_t tl = get<std::uint16_t>(b + 16);
    if (18 + tl + 2 > n) return false;
    r.topic.assign(reinterpret_cast<const char*>(b + 18), tl);
    const std::size_t yl = get<std::uint16_t>(b + 18 + tl);
    const std::size_t at = 20 + tl;
    if (at + yl > n) return false;
    r.type.assign(reinterpret_cast<const char*>(b + at), yl);
    r.payload.assign(b + at + yl, b + n);
    return true;
}

}  // namespace

LinkJournal::LinkJournal(std::string dir, JournalConfig config)
    : dir_(std::move(dir)), config_(config) {
    if (config_.segment_bytes == 0) config_.segment_bytes = 1;
    std::error_code ec;
    fs::create_directories(dir_, ec);
    if (ec) throw common::IoError(dir_, "cannot create the journal folder: " + ec.message());
    {
        std::ifstream in(dir_ + "/released");
        unsigned long long v = 0;
        if (in >> v) released_ = v;
    }
    std::vector<std::string> files;
    for (const auto& e : fs::directory_iterator(dir_, ec)) {
        const std::string name = e.path().filename().string();
        if (name.rfind("seg-", 0) == 0 && e.path().extension() == ".ltmj")
            files.push_back(e.path().string());
    }
    if (ec) throw common::IoError(dir_, "cannot list the journal folder: " + ec.message());
    std::sort(files.begin(), files.end());
    for (const std::string& f : files) load_segment(f);
    // Records already acknowledged before the journal was closed stay forgotten.
    while (!index_.empty() && index_.front().seq <= released_) {
        --segments_[index_.front().segment - segment_base_].records;
        bytes_ -= index_.front().length;
        index_.pop_front();
    }
    while (!segments_.empty() && segments_.front().records == 0) drop_front_segment();
    last_seq_ = std::max(last_seq_, released_);
}

LinkJournal::~LinkJournal() {
    if (out_) std::fclose(out_);
}

void LinkJournal::load_segment(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw common::IoError(path, "cannot open: " + sys_error());
    std::vector<std::uint8_t> data((std::istreambuf_iterator<char>(in)),
                                   std::istreambuf_iterator<char>());
    Segment seg;
    seg.path = path;
    const std::size_t number = segment_base_ + segments_.size();
    std::uint64_t off = 0;
    std::string problem;
    JournalRecord r;
    while (off < data.size()) {
        if (data.size() - off < kHead) {
            problem = "a record cut short";
            break;
        }
        const std::uint32_t magic = get<std::uint32_t>(&data[off]);
        const std::uint32_t len = get<std::uint32_t>(&data[off + 4]);
        const std::uint32_t crc = get<std::uint32_t>(&data[off + 8]);
        if (magic != kMagic || len > kMaxBody) {
            problem = "not a journal record";
            break;
        }
        if (data.size() - off - kHead < len) {
            problem = "a record cut short";
            break;
        }
        const std::uint8_t* body = &data[off + kHead];
        if (common::crc32(body, len) != crc || !parse_body(body, len, r)) {
            problem = "a damaged record";
            break;
        }
        if (r.seq <= last_seq_) {
            problem = "seq " + std::to_string(r.seq) + " out of order";
            break;
        }
        if (seg.records == 0) seg.first_seq = r.seq;
        index_.push_back({r.seq, number, off, kHead + len});
        bytes_ += kHead + len;
        last_seq_ = r.seq;
        ++seg.records;
        off += kHead + len;
    }
    seg.bytes = off;
    if (!problem.empty()) {
        recovery_ += (recovery_.empty() ? "" : "; ") + path + ": " + problem + " at byte " +
                     std::to_string(off) + ", " + std::to_string(data.size() - off) +
                     " bytes cut off";
        if (::truncate(path.c_str(), static_cast<off_t>(off)) != 0)
            throw common::IoError(path, "cannot cut off a damaged tail: " + sys_error());
    }
    if (seg.records == 0) {
        std::error_code ec;
        fs::remove(path, ec);
        return;
    }
    segments_.push_back(seg);
}

void LinkJournal::drop_front_segment() {
    std::error_code ec;
    fs::remove(segments_.front().path, ec);
    if (out_ && segments_.size() == 1) {
        std::fclose(out_);
        out_ = nullptr;
    }
    segments_.pop_front();
    ++segment_base_;
}

void LinkJournal::open_for_append(std::uint64_t first_seq) {
    if (out_) std::fclose(out_);
    out_ = nullptr;
    Segment seg;
    seg.path = dir_ + "/" + segment_name(first_seq);
    seg.first_seq = first_seq;
    out_ = std::fopen(seg.path.c_str(), "ab");
    if (!out_) throw common::IoError(seg.path, "cannot create: " + sys_error());
    segments_.push_back(seg);
}

std::size_t LinkJournal::append(const JournalRecord& r) {
    if (r.seq <= last_seq_)
        throw std::invalid_argument("journal " + dir_ + ": seq " + std::to_string(r.seq) +
                                    " is not above the last one (" + std::to_string(last_seq_) +
                                    ")");
    if (r.topic.size() > 65535 || r.type.size() > 65535)
        throw std::invalid_argument("journal " + dir_ + ": topic or type name too long");
    std::vector<std::uint8_t> rec;
    rec.reserve(kHead + kFixed + r.topic.size() + r.type.size() + r.payload.size());
    put<std::uint32_t>(rec, kMagic);
    put<std::uint32_t>(rec, 0);
    put<std::uint32_t>(rec, 0);
    put<std::uint64_t>(rec, r.seq);
    put<std::int64_t>(rec, r.stamp_ns);
    put<std::uint16_t>(rec, static_cast<std::uint16_t>(r.topic.size()));
    rec.insert(rec.end(), r.topic.begin(), r.topic.end());
    put<std::uint16_t>(rec, static_cast<std::uint16_t>(r.type.size()));
    rec.insert(rec.end(), r.type.begin(), r.type.end());
    rec.insert(rec.end(), r.payload.begin(), r.payload.end());
    const std::uint64_t body = rec.size() - kHead;
    if (body > kMaxBody) throw std::invalid_argument("journal " + dir_ + ": record over 1 GiB");
    const std::uint32_t len = static_cast<std::uint32_t>(body);
    const std::uint32_t crc = common::crc32(rec.data() + kHead, body);
    std::memcpy(&rec[4], &len, 4);
    std::memcpy(&rec[8], &crc, 4);

    // Appending goes to the last segment, unless it is full or was written by an earlier run
    // (reopened journals start a new segment: a cut-off tail never sits before new records).
    if (!out_ || segments_.empty() || segments_.back().bytes >= config_.segment_bytes)
        open_for_append(r.seq);
    Segment& seg = segments_.back();
    if (std::fwrite(rec.data(), 1, rec.size(), out_) != rec.size() || std::fflush(out_) != 0) {
        const std::string why = sys_error();
        // Leave the file as it was: a partial record would end the segment when reopened. The
        // stream is closed first (its close flushes what its buffer still holds), then cut back.
        std::fclose(out_);
        out_ = nullptr;
        if (::truncate(seg.path.c_str(), static_cast<off_t>(seg.bytes)) != 0) {
        }
        // A segment this append opened holds nothing: it goes, or the retry of the same seq would
        // open a second entry on the same file (and releasing the empty one would delete both).
        if (seg.records == 0) {
            std::error_code ec;
            fs::remove(seg.path, ec);
            segments_.pop_back();
        }
        throw common::IoError(seg.path, "cannot append: " + why);
    }
    if (seg.records == 0) seg.first_seq = r.seq;
    index_.push_back({r.seq, segment_base_ + segments_.size() - 1, seg.bytes, rec.size()});
    seg.bytes += rec.size();
    ++seg.records;
    bytes_ += rec.size();
    last_seq_ = r.seq;

    std::size_t dropped = 0;
    while (bytes_ > config_.max_bytes && segments_.size() > 1) {
        const std::size_t front = segment_base_;
        while (!index_.empty() && index_.front().segment == front) {
            bytes_ -= index_.front().length;
            index_.pop_front();
            ++dropped;
        }
        drop_front_segment();
    }
    return dropped;
}

void LinkJournal::sync() {
    if (out_ && ::fsync(fileno(out_)) != 0)
        throw common::IoError(segments_.back().path, "cannot sync: " + sys_error());
}

std::optional<JournalRecord> LinkJournal::read_from(std::uint64_t seq) const {
    const auto it = std::lower_bound(index_.begin(), index_.end(), seq,
                                     [](const Entry& e, std::uint64_t s) { return e.seq < s; });
    if (it == index_.end()) return std::nullopt;
    const Segment& seg = segments_[it->segment - segment_base_];
    std::ifstream in(seg.path, std::ios::binary);
    std::vector<std::uint8_t> data(it->length);
    if (!in || !in.seekg(static_cast<std::streamoff>(it->offset)) ||
        !in.read(reinterpret_cast<char*>(data.data()), static_cast<std::streamsize>(it->length)))
        throw common::IoError(
            seg.path, "cannot read record " + std::to_string(it->seq) + " back: " + sys_error());
    JournalRecord r;
    const std::uint32_t crc = get<std::uint32_t>(&data[8]);
    if (common::crc32(&data[kHead], data.size() - kHead) != crc ||
        !parse_body(&data[kHead], data.size() - kHead, r))
        throw common::IoError(seg.path, "record " + std::to_string(it->seq) +
                                            " changed on disk since it was written");
    return r;
}

void LinkJournal::release_through(std::uint64_t seq) {
    if (seq <= released_) return;
    released_ = seq;
    last_seq_ = std::max(last_seq_, released_);  // as a reopen reads it back: appends go above
    while (!index_.empty() && index_.front().seq <= seq) {
        --segments_[index_.front().segment - segment_base_].records;
        bytes_ -= index_.front().length;
        index_.pop_front();
    }
    // Whole segments go; the one being appended to stays until a new one starts.
    while (!segments_.empty() && segments_.front().records == 0 && (segments_.size() > 1 || !out_))
        drop_front_segment();
    common::write_file_atomic(dir_ + "/released", std::to_string(released_) + "\n");
}

}  // namespace ltm::link
