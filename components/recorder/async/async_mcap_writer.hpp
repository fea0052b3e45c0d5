#pragma once
// AsyncMcapWriter: puts a bounded queue and a writer thread in front of McapWriter so that the
// producer (a DDS listener) never waits for compression or the disk. When the queue is full the
// new message is dropped and counted (per topic); the counts are reported, never hidden. After a
// write error (disk full) the file is already closed cleanly by McapWriter, recording stops and
// every later message is counted as dropped.
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "recorder/core/mcap_writer.hpp"

namespace ltm::recorder {

struct AsyncWriterConfig {
    std::size_t max_queue_bytes = std::size_t{512} << 20;  // payload bytes waiting to be written
    std::size_t max_queue_messages = 10000;                // messages waiting to be written
    double idle_flush_s = 1.0;     // close the open chunk after this long without a message
    double report_period_s = 1.0;  // at most one drop report per period
    std::string thread_name;       // the writing thread's name (15 characters; "": inherited)
};

struct AsyncWriterStats {
    std::uint64_t accepted = 0;               // messages queued
    std::uint64_t written = 0;                // messages handed to McapWriter successfully
    std::uint64_t dropped_queue_full = 0;     // the disk could not keep up
    std::uint64_t dropped_after_failure = 0;  // arrived after a write error or close()
    std::map<std::string, std::uint64_t> dropped_by_topic;  // both kinds of drop
    std::size_t queued_messages = 0, queued_bytes = 0, peak_queued_bytes = 0;
    bool failed = false;
    std::string error;   // one line when failed
    WriterStats writer;  // McapWriter's counters (messages in the file, chunks, bytes)
    std::uint64_t dropped() const { return dropped_queue_full + dropped_after_failure; }
};

class AsyncMcapWriter {
  public:
    using Report = std::function<void(const std::string& line)>;

    // Takes the writer over and starts the writer thread. `report` (optional) is called from the
    // writer thread with one line when messages are dropped (at most once a report period) and
    // when writing fails.
    explicit AsyncMcapWriter(std::unique_ptr<McapWriter> writer, AsyncWriterConfig config = {},
                             Report report = {});
    ~AsyncMcapWriter();  // close()
    AsyncMcapWriter(const AsyncMcapWriter&) = delete;
    AsyncMcapWriter& operator=(const AsyncMcapWriter&) = delete;

    // Thread-safe registration (never dropped); ids 1, 2, 3 ... as McapWriter assigns them.
    // Throws std::invalid_argument for an unknown schema id or too many ids.
    std::uint16_t add_schema(const std::string& name, const std::string& encoding,
                             const std::string& data);
    std::uint16_t add_channel(std::uint16_t schema_id, const std::string& topic,
                              const std::string& message_encoding = "cdr",
                              const std::map<std::string, std::string>& metadata = {});

    // Queues a copy of the message, or drops it (counted). Never waits for the disk; true when
    // queued. Thread-safe.
    bool push(std::uint16_t channel_id, std::uint64_t log_time, std::uint64_t publish_time,
              const void* data, std::size_t size);
    bool push(std::uint16_t channel_id, std::uint64_t log_time, std::uint64_t publish_time,
              std::vector<std::uint8_t>&& data);

    AsyncWriterStats stats() const;
    // Writes what is queued, closes the file and stops the thread; returns the final counters.
    AsyncWriterStats close();

  private:
    struct Item {
        enum class Kind { kMessage, kSchema, kChannel } kind = Kind::kMessage;
        std::uint16_t channel_id = 0;
        std::uint64_t log_time = 0, publish_time = 0;
        std::vector<std::uint8_t> data;
        Schema schema;
        Channel channel;
    };
    bool admit(std::uint16_t channel_id, std::size_t size);   // under lock
    void drop(std::uint16_t channel_id, bool after_failure);  // under lock
    void enqueue(Item&& item);
    void run();
    void maybe_report(std::unique_lock<std::mutex>& lock, bool force);

    std::unique_ptr<McapWriter> writer_;
    AsyncWriterConfig config_;
    Report report_;
    mutable std::mutex mutex_;
    std::condition_variable cv_;
    std::deque<Item> queue_;
    std::vector<std::vector<std::uint8_t>> pool_;  // payload buffers to reuse
    std::map<std::uint16_t, std::string> topics_;
    std::uint16_t next_schema_ = 1, next_channel_ = 1;
    std::map<std::uint16_t, bool> schema_known_;
    AsyncWriterStats stats_;
    std::uint64_t reported_drops_ = 0;
    std::chrono::steady_clock::time_point last_report_{};
    bool closing_ = false, closed_ = false;
    std::thread thread_;
};

}  // namespace ltm::recorder
