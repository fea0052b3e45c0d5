#pragma once
// McapReader: opens an MCAP file through its summary (chunk index) when the file has an intact
// one, else by a linear scan of the records (files cut short, unindexed files). Damage is
// reported as one line with its byte offset (problem()); whatever is intact stays readable.
//
//   McapReader reader("run.mcap");                 // throws common::IoError if not MCAP at all
//   if (!reader.problem().empty()) std::cerr << reader.problem() << "\n";
//   MessageCursor cursor = reader.messages({{"rt/points"}, t0, t1});
//   for (MessageView m; cursor.next(m);) use(m.channel->topic, m.data, m.size, m.log_time);
#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "recorder/core/mcap_records.hpp"
#include "recorder/core/mcap_scan.hpp"
#include "recorder/core/message_cursor.hpp"

namespace ltm::recorder {

struct ReadOptions {
    std::vector<std::string> topics;                                     // empty: every topic
    std::uint64_t start_time = 0;                                        // ns, inclusive
    std::uint64_t end_time = std::numeric_limits<std::uint64_t>::max();  // ns, inclusive
    bool check_crcs = true;                                              // chunk CRCs
};

struct VerifyReport {
    bool ok = false;
    std::vector<std::string> problems;  // one line each, with byte offsets
    std::uint64_t messages = 0;
    std::uint64_t chunks = 0;
};

class McapReader {
  public:
    // Throws common::IoError (one line) when the file cannot be opened or is not MCAP.
    explicit McapReader(const std::string& path);
    ~McapReader();
    McapReader(const McapReader&) = delete;
    McapReader& operator=(const McapReader&) = delete;

    const std::string& path() const { return file_->path(); }
    std::uint64_t file_size() const { return file_->size(); }
    bool indexed() const { return indexed_; }    // read through the summary's chunk index
    bool complete() const { return complete_; }  // footer and summary present and intact
    // The first problem found, one line ("what, at byte N"); empty while the file is intact.
    std::string problem() const { return problems_.empty() ? std::string() : problems_.front(); }
    const std::vector<std::string>& problems() const { return problems_; }
    void report(const std::string& problem);  // adds a problem found while reading messages

    const Header& header() const { return header_; }
    const std::map<std::uint16_t, Schema>& schemas() const { return schemas_; }
    const std::map<std::uint16_t, Channel>& channels() const { return channels_; }
    const std::vector<ChunkInfo>& chunks() const { return chunks_; }  // in file order
    // From the summary when present, else counted by the scan (always counts of readable data).
    const Statistics& statistics() const { return statistics_; }
    const FileSource& file() const { return *file_; }
    // Adds records met inside chunks while reading (no-op when already known).
    void learn(const Schema& s) { schemas_.emplace(s.id, s); }
    void learn(const Channel& c) { channels_.emplace(c.id, c); }

    // Messages in log-time order (ties in chunk order, then file order). The cursor refers to
    // this reader, which must outlive it.
    MessageCursor messages(const ReadOptions& options = {});

    // Reads the whole file and checks everything: data-section CRC, every chunk CRC, message
    // indexes against chunk contents, and the summary (chunk index, statistics, channels)
    // against the data. Slow (reads and decompresses every byte).
    VerifyReport verify() const;

  private:
    bool open_summary();
    void adopt_scan(ScanResult&& scan);

    std::unique_ptr<FileSource> file_;
    bool indexed_ = false;
    bool complete_ = false;
    bool cut_short_ = false;  // no Footer/end magic
    std::vector<std::string> problems_;
    Header header_;
    Footer footer_;
    std::map<std::uint16_t, Schema> schemas_;
    std::map<std::uint16_t, Channel> channels_;
    std::vector<ChunkInfo> chunks_;
    Statistics statistics_;
};

}  // namespace ltm::recorder
