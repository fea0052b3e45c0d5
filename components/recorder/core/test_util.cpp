#include "recorder/core/test_util.hpp"

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <random>
#include <stdexcept>

namespace ltm::recorder::test {

TempDir::TempDir(const std::string& name) {
#ifdef LTM_BINARY_DIR
    const std::string root = std::string(LTM_BINARY_DIR) + "/test_tmp";
#else
    const std::string root = "/tmp";
#endif
    path_ = root + "/" + name + "_" + std::to_string(::getpid());
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
}

TempDir::~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
}

TestRecording make_recording(std::size_t n, std::size_t max_size, std::uint64_t seed) {
    TestRecording rec;
    rec.schemas.push_back(Schema{1, "test::msg::dds_::Points_", "omgidl",
                                 "module test { module msg { module dds_ { struct Points_ { "
                                 "sequence<float> xyz; }; }; }; };"});
    rec.schemas.push_back(Schema{2, "test::msg::dds_::Pose_", "omgidl",
                                 "module test { module msg { module dds_ { struct Pose_ { "
                                 "double p[7]; }; }; }; };"});
    rec.channels.push_back(Channel{1, 1, "rt/points", "cdr", {{"qos", "sensor"}}});
    rec.channels.push_back(Channel{2, 2, "rt/pose", "cdr", {}});
    rec.channels.push_back(Channel{3, 0, "rt/log", "json", {}});
    std::mt19937_64 rng(seed);
    std::uint32_t seq[4] = {0, 0, 0, 0};
    for (std::size_t i = 0; i < n; ++i) {
        TestMessage m;
        m.channel = static_cast<std::uint16_t>(1 + rng() % 3);
        m.topic = rec.channels[m.channel - 1].topic;
        m.sequence = ++seq[m.channel];
        m.log_time = 1000000000ull + i * 1000000ull;
        m.publish_time = m.log_time - rng() % 1000;
        const std::size_t size = i % 17 == 5 ? 0 : rng() % (max_size + 1);
        m.data.resize(size);
        // Half compressible (ramps), half noise.
        for (std::size_t k = 0; k < size; ++k) {
            m.data[k] = k % 2 ? static_cast<std::uint8_t>(k / 7) : static_cast<std::uint8_t>(rng());
        }
        rec.messages.push_back(std::move(m));
    }
    // Out of order writes: swap some neighbours, and give two messages the same log time.
    for (std::size_t i = 0; i + 1 < n; i += 7) std::swap(rec.messages[i], rec.messages[i + 1]);
    if (n > 20) rec.messages[20].log_time = rec.messages[19].log_time;
    return rec;
}

WriteStatus write_recording(const std::string& path, const TestRecording& rec,
                            const McapWriterConfig& config) {
    McapWriter w(path, config);
    for (const auto& s : rec.schemas) w.add_schema(s.name, s.encoding, s.data);
    for (const auto& c : rec.channels)
        w.add_channel(c.schema_id, c.topic, c.message_encoding, c.metadata);
    for (const auto& m : rec.messages) {
        const WriteStatus st = w.write(m.channel, m.log_time, m.publish_time, m.data.data(),
                                       m.data.size(), m.sequence);
        if (st != WriteStatus::kOk) return st;
    }
    return w.close();
}

std::vector<TestMessage> by_log_time(const std::vector<TestMessage>& messages) {
    std::vector<TestMessage> sorted = messages;
    std::stable_sort(sorted.begin(), sorted.end(), [](const TestMessage& a, const TestMessage& b) {
        return a.log_time < b.log_time;
    });
    return sorted;
}

std::vector<std::uint8_t> read_file(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    if (!f) throw std::runtime_error("cannot read " + path);
    return std::vector<std::uint8_t>((std::istreambuf_iterator<char>(f)), {});
}

void write_file(const std::string& path, const std::vector<std::uint8_t>& bytes) {
    std::ofstream f(path, std::ios::binary | std::ios::trunc);
    f.write(reinterpret_cast<const char*>(bytes.data()),
            static_cast<std::streamsize>(bytes.size()));
}

}  // namespace ltm::recorder::test
