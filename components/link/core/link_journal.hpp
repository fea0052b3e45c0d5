#pragma once
// The link's store-and-forward log: an append-only journal of messages on disk, in segment files
// of a few MiB. The robot's uplink keeps here what the base station has not acknowledged yet; the
// base station's downlink keeps everything it received (what a restarted base station replays).
//
// A record: magic "LTMJ", body length (u32), CRC-32 of the body (u32), then the body: seq (u64),
// stamp (i64 ns), topic and type (u16 length + bytes each), payload (the rest). Opening a journal
// reads every segment back; a record cut short or damaged (a crash while writing) ends its
// segment: the file is truncated there and what was lost is reported in recovery().
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <deque>
#include <optional>
#include <string>
#include <vector>

namespace ltm::link {

struct JournalRecord {
    std::uint64_t seq = 0;
    std::int64_t stamp_ns = 0;
    std::string topic;  // relative to the robot's namespace
    std::string type;   // DDS type name
    std::vector<std::uint8_t> payload;
};

struct JournalConfig {
    std::uint64_t segment_bytes = 8ull << 20;  // a new segment file after this many bytes
    // Bound of the records held: beyond it the oldest segments are dropped (reported by append).
    std::uint64_t max_bytes = 4ull << 30;
};

class LinkJournal {
  public:
    // Opens (creating the folder) and reads back what is there. Throws common::IoError when the
    // folder cannot be made or read, or a segment cannot be opened.
    explicit LinkJournal(std::string dir, JournalConfig config = {});
    ~LinkJournal();
    LinkJournal(const LinkJournal&) = delete;
    LinkJournal& operator=(const LinkJournal&) = delete;

    // Appends a record; its seq must be above last_seq() (gaps are allowed). Returns the number
    // of records dropped (oldest first) to stay within max_bytes. Throws common::IoError when the
    // disk refuses the write (nothing is then recorded) and std::invalid_argument for a seq out of
    // order or a topic/type longer than 65535 bytes.
    std::size_t append(const JournalRecord& record);
    // Flushes appended records to the disk (fsync).
    void sync();

    bool empty() const { return index_.empty(); }
    std::size_t size() const { return index_.size(); }
    std::uint64_t first_seq() const { return index_.empty() ? 0 : index_.front().seq; }
    std::uint64_t last_seq() const { return last_seq_; }
    std::uint64_t bytes() const { return bytes_; }
    const std::string& dir() const { return dir_; }

    // The held record with the smallest seq >= `seq`. Throws common::IoError when its file
    // cannot be read back.
    std::optional<JournalRecord> read_from(std::uint64_t seq) const;
    // Forgets every record with seq <= `seq`; a segment file goes once all its records are
    // forgotten. What is forgotten stays forgotten across a reopen (`released` file), and
    // last_seq() is at least `seq` from then on (appends go above it).
    void release_through(std::uint64_t seq);
    std::uint64_t released_through() const { return released_; }

    // What opening found: "" when every segment was whole.
    const std::string& recovery() const { return recovery_; }

  private:
    struct Entry {
        std::uint64_t seq = 0;
        std::size_t segment = 0;  // index into segments_ (shifted as segments go)
        std::uint64_t offset = 0, length = 0;
    };
    struct Segment {
        std::string path;
        std::uint64_t first_seq = 0, bytes = 0;
        std::size_t records = 0;  // records still held
    };
    void load_segment(const std::string& path);
    void drop_front_segment();
    void open_for_append(std::uint64_t first_seq);

    std::string dir_;
    JournalConfig config_;
    std::deque<Segment> segments_;
    std::size_t segment_base_ = 0;  // segments_[i] is segment number segment_base_ + i
    std::deque<Entry> index_;
    std::FILE* out_ = nullptr;  // the last segment, open for appending
    std::uint64_t last_seq_ = 0, bytes_ = 0, released_ = 0;
    std::string recovery_;
};

}  // namespace ltm::link
