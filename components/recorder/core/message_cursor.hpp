#pragma once
// MessageCursor: the messages of an McapReader in log-time order, within a time window and on
// chosen topics. Loads only the chunks whose time range meets the window, a few at a time
// (chunks that overlap in time are merged with a heap).
#include <cstddef>
#include <cstdint>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "recorder/core/mcap_records.hpp"

namespace ltm::recorder {

class McapReader;
struct ReadOptions;

struct MessageView {
    const Channel* channel = nullptr;
    const Schema* schema = nullptr;  // nullptr when the channel has no schema
    std::uint32_t sequence = 0;
    std::uint64_t log_time = 0;          // ns
    std::uint64_t publish_time = 0;      // ns
    const std::uint8_t* data = nullptr;  // valid until the next call to next()
    std::size_t size = 0;
};

class MessageCursor {
  public:
    MessageCursor(McapReader& reader, const ReadOptions& options);
    ~MessageCursor();
    MessageCursor(MessageCursor&&) noexcept;
    MessageCursor& operator=(MessageCursor&&) = delete;
    MessageCursor(const MessageCursor&) = delete;

    // The next message; false when there are no more. A chunk that cannot be read is reported
    // to the reader (McapReader::problems()) and skipped.
    bool next(MessageView& out);
    std::size_t chunks_loaded() const { return chunks_loaded_; }
    std::size_t chunks_selected() const { return order_.size(); }

  private:
    struct Loaded;
    struct Head {  // a loaded chunk's next message, ordered by (log_time, chunk rank, offset)
        std::uint64_t log_time;
        std::size_t rank;
        std::size_t offset;
        std::size_t slot;
    };
    void load(std::size_t chunk);
    void push_head(std::size_t slot);

    McapReader* reader_;
    std::uint64_t start_time_, end_time_;
    bool check_crcs_;
    bool all_channels_ = true;
    std::set<std::string> topics_;
    std::set<std::uint16_t> wanted_;
    std::vector<std::size_t> order_;  // chunks to read, by start time
    std::size_t next_chunk_ = 0;
    std::vector<std::unique_ptr<Loaded>> slots_;
    std::vector<Head> heap_;
    std::size_t retire_ = static_cast<std::size_t>(-1);  // slot to free on the next call
    std::size_t chunks_loaded_ = 0;
};

}  // namespace ltm::recorder
