#pragma once
// Helpers shared by the recorder tests: temporary folders, deterministic messages, file edits.
#include <cstdint>
#include <string>
#include <vector>

#include "recorder/core/mcap_writer.hpp"

namespace ltm::recorder::test {

// A fresh folder under the build tree (or /tmp), removed when the object dies.
class TempDir {
  public:
    explicit TempDir(const std::string& name);
    ~TempDir();
    std::string file(const std::string& name) const { return path_ + "/" + name; }

  private:
    std::string path_;
};

struct TestMessage {
    std::uint16_t channel = 0;  // index into the channels written (1-based ids)
    std::string topic;
    std::uint32_t sequence = 0;
    std::uint64_t log_time = 0, publish_time = 0;
    std::vector<std::uint8_t> data;
};

struct TestRecording {
    std::vector<Schema> schemas;
    std::vector<Channel> channels;
    std::vector<TestMessage> messages;  // in write order
};

// n messages over 3 channels (2 schemas + one schema-less channel), sizes 0..max_size, log times
// 1 ms apart with some written out of order, fixed seed.
TestRecording make_recording(std::size_t n, std::size_t max_size, std::uint64_t seed);
// Writes it; returns the writer's status of close().
WriteStatus write_recording(const std::string& path, const TestRecording& rec,
                            const McapWriterConfig& config);
// Messages sorted by (log_time, write order): what a reader must return.
std::vector<TestMessage> by_log_time(const std::vector<TestMessage>& messages);

std::vector<std::uint8_t> read_file(const std::string& path);
void write_file(const std::string& path, const std::vector<std::uint8_t>& bytes);

}  // namespace ltm::recorder::test
