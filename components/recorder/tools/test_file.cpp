// The deterministic file of the independent-reader test, and the manifest of what it holds.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "recorder/core/mcap_writer.hpp"
#include "recorder/tools/manifest.hpp"

namespace ltm::recorder::tools {
namespace {

const char* kPointsIdl = R"(module ltm_test {
  module msg {
    module dds_ {
      struct Point_ {
        float x;
        float y;
        float z;
        float intensity;
      };
      struct Points_ {
        unsigned long long stamp_ns;
        string frame_id;
        sequence<ltm_test::msg::dds_::Point_> points;
      };
    };
  };
};
)";

const char* kOdometryIdl = R"(module ltm_test {
  module msg {
    module dds_ {
      struct Odometry_ {
        unsigned long long stamp_ns;
        double position[3];
        double orientation[4];
      };
    };
  };
};
)";

// Little-endian XCDR1 (plain CDR) encoder: 4-byte encapsulation header, alignment from its end.
class Cdr {
  public:
    Cdr() { bytes_ = {0x00, 0x01, 0x00, 0x00}; }
    template <typename T>
    void put(T v) {
        while ((bytes_.size() - 4) % sizeof(T) != 0) bytes_.push_back(0);
        const auto* p = reinterpret_cast<const std::uint8_t*>(&v);
        bytes_.insert(bytes_.end(), p, p + sizeof(T));
    }
    void str(const std::string& s) {
        put<std::uint32_t>(static_cast<std::uint32_t>(s.size() + 1));
        bytes_.insert(bytes_.end(), s.begin(), s.end());
        bytes_.push_back(0);
    }
    std::vector<std::uint8_t>& bytes() { return bytes_; }

  private:
    std::vector<std::uint8_t> bytes_;
};

struct Written {
    std::uint16_t channel;
    std::string topic;
    std::uint32_t sequence;
    std::uint64_t log_time, publish_time;
    std::vector<std::uint8_t> data;
};

}  // namespace

void write_test_file(const std::string& path, const TestFileOptions& options,
                     std::ostream& manifest) {
    McapWriterConfig config;
    config.compression = options.compression;
    config.chunk_size = options.chunk_size;
    McapWriter writer(path, config);
    const std::uint16_t points_schema =
        writer.add_schema("ltm_test::msg::dds_::Points_", "omgidl", kPointsIdl);
    const std::uint16_t odom_schema =
        writer.add_schema("ltm_test::msg::dds_::Odometry_", "omgidl", kOdometryIdl);
    const std::uint16_t points = writer.add_channel(points_schema, "rt/robot/points", "cdr",
                                                    {{"qos", "best_effort"}, {"frame", "lidar"}});
    const std::uint16_t odom = writer.add_channel(odom_schema, "rt/robot/odometry", "cdr");
    const std::uint16_t diag = writer.add_channel(0, "rt/robot/diagnostics", "json");
    const std::string topics[] = {"", "rt/robot/points", "rt/robot/odometry",
                                  "rt/robot/diagnostics"};

    std::uint64_t state = 0x2545F4914F6CDD1Dull;  // xorshift64: fixed, platform independent
    auto rnd = [&]() {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        return state;
    };
    std::vector<Written> msgs;
    std::uint32_t seq[4] = {0, 0, 0, 0};
    const std::uint64_t t0 = 1700000000000000000ull;
    for (std::size_t i = 0; i < options.messages; ++i) {
        Written w;
        w.log_time = t0 + i * 10000000ull + rnd() % 1000;  // 10 ms apart: unique, increasing
        w.publish_time = w.log_time - 200000 - rnd() % 100000;
        Cdr cdr;
        if (i % 3 == 0) {
            w.channel = points;
            cdr.put<std::uint64_t>(w.publish_time);
            cdr.str("lidar");
            const std::uint32_t n = static_cast<std::uint32_t>(rnd() % 1800);
            cdr.put<std::uint32_t>(n);
            for (std::uint32_t k = 0; k < n; ++k) {
                const float ring = static_cast<float>(k % 64);
                cdr.put<float>(10.0f * std::cos(0.01f * static_cast<float>(k)));
                cdr.put<float>(10.0f * std::sin(0.01f * static_cast<float>(k)));
                cdr.put<float>(-1.5f + 0.05f * ring);
                cdr.put<float>(static_cast<float>(rnd() % 256));
            }
            w.data = std::move(cdr.bytes());
        } else if (i % 3 == 1) {
            w.channel = odom;
            cdr.put<std::uint64_t>(w.publish_time);
            for (int k = 0; k < 7; ++k) cdr.put<double>(static_cast<double>(rnd() % 100000) * 1e-3);
            w.data = std::move(cdr.bytes());
        } else {
            w.channel = diag;
            const std::string text =
                i % 30 == 2 ? std::string() : "{\"seq\": " + std::to_string(i) + "}";
            w.data.assign(text.begin(), text.end());
        }
        w.topic = topics[w.channel];
        w.sequence = ++seq[w.channel];
        msgs.push_back(std::move(w));
    }
    // Write slightly out of log-time order: readers must sort.
    std::vector<std::size_t> order(msgs.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    for (std::size_t i = 0; i + 1 < order.size(); i += 10) std::swap(order[i], order[i + 1]);
    for (const std::size_t i : order) {
        const Written& w = msgs[i];
        if (writer.write(w.channel, w.log_time, w.publish_time, w.data.data(), w.data.size(),
                         w.sequence) != WriteStatus::kOk) {
            throw std::runtime_error(writer.error());
        }
    }
    if (writer.close() != WriteStatus::kOk) throw std::runtime_error(writer.error());

    // The manifest of what was written (independent of ltm's reader).
    manifest << "{\n  \"schemas\": [";
    bool first = true;
    for (const auto& [id, s] : writer.schemas()) {
        manifest << (first ? "\n" : ",\n") << "    {\"id\": " << id << ", \"name\": \""
                 << json_escape(s.name) << "\", \"encoding\": \"" << s.encoding
                 << "\", \"data_hex\": \"" << hex(s.data.data(), s.data.size()) << "\"}";
        first = false;
    }
    manifest << "\n  ],\n  \"channels\": [";
    first = true;
    for (const auto& [id, c] : writer.channels()) {
        manifest << (first ? "\n" : ",\n") << "    {\"id\": " << id
                 << ", \"schema_id\": " << c.schema_id << ", \"topic\": \"" << c.topic
                 << "\", \"message_encoding\": \"" << c.message_encoding << "\", \"metadata\": {";
        bool first_kv = true;
        for (const auto& [k, v] : c.metadata) {
            manifest << (first_kv ? "" : ", ") << "\"" << k << "\": \"" << v << "\"";
            first_kv = false;
        }
        manifest << "}}";
        first = false;
    }
    manifest << "\n  ],\n  \"messages\": [";
    first = true;
    for (const auto& w : msgs) {  // generated in log-time order
        manifest << (first ? "\n" : ",\n") << "    {\"channel_id\": " << w.channel
                 << ", \"topic\": \"" << w.topic << "\", \"sequence\": " << w.sequence
                 << ", \"log_time\": \"" << w.log_time << "\", \"publish_time\": \""
                 << w.publish_time << "\", \"data_hex\": \"" << hex(w.data.data(), w.data.size())
                 << "\"}";
        first = false;
    }
    manifest << "\n  ]\n}\n";
}

}  // namespace ltm::recorder::tools
