// ltm_mcap_bench: MCAP recording throughput and CPU for LiDAR-sized CDR payloads.
//   ltm_mcap_bench [--frames N] [--seconds S] [--out DIR] [--kitti DIR]
// --frames 0 skips part 1; --out on a small filesystem shows the full-disk behaviour of part 2.
// Payloads: real KITTI HDL-64 scans (~120k points, ~1.9 MB of float32 x y z intensity) behind a
// PointCloud2-like CDR header, cycled; synthetic rings when the data is absent.
// Part 1, flat out: McapWriter alone, as fast as it goes (MB/s, messages/s, CPU, size vs raw),
//         then McapReader reading the file back in log-time order (read MB/s).
// Part 2, 10 Hz: AsyncMcapWriter fed one scan every 100 ms (CPU share, drops, queue peak).
#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "common/cli/cli.hpp"
#include "common/core/kitti_io.hpp"
#include "recorder/async/async_mcap_writer.hpp"
#include "recorder/core/mcap_reader.hpp"
#include "recorder/core/mcap_writer.hpp"

namespace fs = std::filesystem;
using namespace ltm::recorder;
namespace cli = ltm::common::cli;
using Clock = std::chrono::steady_clock;

namespace {

double cpu_seconds() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
           1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

std::vector<std::uint8_t> cdr_cloud(const std::vector<float>& xyzi, std::uint64_t stamp) {
    std::vector<std::uint8_t> b = {0x00, 0x01, 0x00, 0x00};  // XCDR1 little endian
    auto put = [&](const void* p, std::size_t n) {
        while ((b.size() - 4) % (n < 8 ? n : 8) != 0) b.push_back(0);
        const auto* c = static_cast<const std::uint8_t*>(p);
        b.insert(b.end(), c, c + n);
    };
    const std::uint32_t sec = static_cast<std::uint32_t>(stamp / 1000000000ull);
    const std::uint32_t nsec = static_cast<std::uint32_t>(stamp % 1000000000ull);
    put(&sec, 4);
    put(&nsec, 4);
    const std::string frame = "velodyne";
    const std::uint32_t flen = static_cast<std::uint32_t>(frame.size() + 1);
    put(&flen, 4);
    b.insert(b.end(), frame.begin(), frame.end());
    b.push_back(0);
    const std::uint32_t height = 1, width = static_cast<std::uint32_t>(xyzi.size() / 4);
    put(&height, 4);
    put(&width, 4);
    const std::uint32_t nfields = 4;
    put(&nfields, 4);
    const char* names[] = {"x", "y", "z", "intensity"};
    for (std::uint32_t i = 0; i < 4; ++i) {
        const std::uint32_t nl = static_cast<std::uint32_t>(std::strlen(names[i]) + 1);
        put(&nl, 4);
        b.insert(b.end(), names[i], names[i] + nl);
        const std::uint32_t offset = 4 * i, count = 1;
        put(&offset, 4);
        b.push_back(7);  // FLOAT32
        put(&count, 4);
    }
    b.push_back(0);  // is_bigendian
    const std::uint32_t point_step = 16, row_step = 16 * width, data_len = row_step;
    put(&point_step, 4);
    put(&row_step, 4);
    put(&data_len, 4);
    const auto* p = reinterpret_cast<const std::uint8_t*>(xyzi.data());
    b.insert(b.end(), p, p + data_len);
    b.push_back(1);  // is_dense
    return b;
}

std::vector<std::vector<std::uint8_t>> load_scans(const std::string& kitti_dir,
                                                  std::string& source) {
    std::vector<std::vector<std::uint8_t>> scans;
    if (fs::is_directory(kitti_dir)) {
        for (const auto& path : ltm::common::list_kitti_scans(kitti_dir)) {
            const auto cloud = ltm::common::read_kitti_bin(path);
            std::vector<float> xyzi;
            xyzi.reserve(cloud.size() * 4);
            for (std::size_t i = 0; i < cloud.size(); ++i) {
                xyzi.insert(xyzi.end(), {cloud.points[i].x(), cloud.points[i].y(),
                                         cloud.points[i].z(), cloud.intensity[i]});
            }
            scans.push_back(cdr_cloud(xyzi, 0));
        }
        source = "KITTI scans from " + kitti_dir;
    }
    if (scans.empty()) {
        std::mt19937 rng(1);
        std::normal_distribution<float> noise(0.0f, 0.02f);
        for (int s = 0; s < 8; ++s) {
            std::vector<float> xyzi;
            for (int ring = 0; ring < 64; ++ring) {
                for (int k = 0; k < 1875; ++k) {
                    const float az = 6.2831853f * static_cast<float>(k) / 1875.0f;
                    const float r =
                        8.0f + 6.0f * std::sin(3.0f * az + static_cast<float>(s)) + noise(rng);
                    const float el = -0.43f + 0.0069f * static_cast<float>(ring);
                    xyzi.insert(xyzi.end(), {r * std::cos(az), r * std::sin(az), r * std::tan(el),
                                             static_cast<float>(rng() % 100) / 100.0f});
                }
            }
            scans.push_back(cdr_cloud(xyzi, 0));
        }
        source = "synthetic 120k-point rings (KITTI data not found)";
    }
    return scans;
}

struct Mode {
    const char* name;
    Compression compression;
    int level;
};

}  // namespace

int main(int argc, char** argv) {
    std::size_t frames = 100;
    double seconds = 10.0;
    std::string out_dir = "/tmp";
    std::string kitti = std::string(LTM_SOURCE_DIR) + "/../shared/data/kitti/sequences/00";
    CLI::App app{"MCAP recording throughput and CPU for LiDAR-sized CDR payloads",
                 "ltm_mcap_bench"};
    cli::configure(app);
    app.add_option("--frames", frames, "scans written flat out (0: skip that part)");
    app.add_option("--seconds", seconds, "duration of the 10 Hz part [s]")->check(cli::at_least(0));
    app.add_option("--out", out_dir, "folder of the temporary recording");
    app.add_option("--kitti", kitti, "KITTI sequence whose scans are the payloads");
    if (const int code = cli::parse(app, argc, argv); code >= 0) return code;
    std::string source;
    const auto scans = load_scans(kitti, source);
    double avg = 0;
    for (const auto& s : scans) avg += static_cast<double>(s.size());
    avg /= static_cast<double>(scans.size());
    std::printf("payloads: %zu distinct, %.2f MB average (%s)\n", scans.size(), avg / 1e6,
                source.c_str());
    const Mode modes[] = {{"zstd-1", Compression::kZstd, 1},
                          {"zstd-3", Compression::kZstd, 3},
                          {"lz4", Compression::kLz4, 0},
                          {"none", Compression::kNone, 0}};
    const std::string path = out_dir + "/ltm_mcap_bench.mcap";

    if (frames > 0) std::printf("\nflat out, McapWriter alone, %zu scans, 4 MiB chunks:\n", frames);
    if (frames > 0) {
        std::printf("%-8s %10s %10s %10s %12s %10s %12s\n", "mode", "MB/s", "msgs/s", "CPU s",
                    "file/raw", "ms/scan", "read MB/s");
    }
    for (const Mode& m : modes) {
        if (frames == 0) break;
        McapWriterConfig c;
        c.compression = m.compression;
        c.compression_level = m.level;
        const double cpu0 = cpu_seconds();
        const auto t0 = Clock::now();
        std::uint64_t raw = 0, file = 0;
        {
            McapWriter w(path, c);
            const auto ch = w.add_channel(
                w.add_schema("sensor_msgs::msg::dds_::PointCloud2_", "omgidl", "..."), "rt/points");
            for (std::size_t i = 0; i < frames; ++i) {
                const auto& s = scans[i % scans.size()];
                const std::uint64_t t = i * 100000000ull;
                if (w.write(ch, t, t, s.data(), s.size()) != WriteStatus::kOk) {
                    std::cerr << w.error() << "\n";
                    return 1;
                }
                raw += s.size();
            }
            if (w.close() != WriteStatus::kOk) {
                std::cerr << w.error() << "\n";
                return 1;
            }
            file = w.stats().file_bytes;
        }
        const double wall = std::chrono::duration<double>(Clock::now() - t0).count();
        const double cpu = cpu_seconds() - cpu0;
        // Reading it back (what replay does): every message in log-time order, CRCs checked.
        const auto r0 = Clock::now();
        std::uint64_t read_bytes = 0;
        {
            McapReader reader(path);
            MessageCursor cursor = reader.messages();
            for (MessageView v; cursor.next(v);) read_bytes += v.size;
        }
        const double read_wall = std::chrono::duration<double>(Clock::now() - r0).count();
        if (read_bytes != raw) {
            std::cerr << "read back " << read_bytes << " bytes, wrote " << raw << "\n";
            return 1;
        }
        std::printf("%-8s %10.1f %10.1f %10.2f %12.3f %10.1f %12.1f\n", m.name,
                    static_cast<double>(raw) / 1e6 / wall, static_cast<double>(frames) / wall, cpu,
                    static_cast<double>(file) / static_cast<double>(raw),
                    1e3 * wall / static_cast<double>(frames),
                    static_cast<double>(raw) / 1e6 / read_wall);
    }

    const std::size_t live = static_cast<std::size_t>(seconds * 10.0);
    std::printf("\n10 Hz for %.0f s through AsyncMcapWriter (%zu scans; CPU = whole process):\n",
                seconds, live);
    std::printf("%-8s %10s %10s %10s %12s %12s\n", "mode", "CPU %", "MB/s", "dropped", "queue peak",
                "file/raw");
    for (const Mode& m : modes) {
        McapWriterConfig c;
        c.compression = m.compression;
        c.compression_level = m.level;
        AsyncMcapWriter w(std::make_unique<McapWriter>(path, c));
        const auto ch = w.add_channel(
            w.add_schema("sensor_msgs::msg::dds_::PointCloud2_", "omgidl", "..."), "rt/points");
        const double cpu0 = cpu_seconds();
        const auto t0 = Clock::now();
        std::uint64_t raw = 0;
        for (std::size_t i = 0; i < live; ++i) {
            std::this_thread::sleep_until(t0 + std::chrono::milliseconds(100 * i));
            const auto& s = scans[i % scans.size()];
            const std::uint64_t t = i * 100000000ull;
            w.push(ch, t, t, s.data(), s.size());
            raw += s.size();
        }
        const AsyncWriterStats st = w.close();
        const double wall = std::chrono::duration<double>(Clock::now() - t0).count();
        const double cpu = cpu_seconds() - cpu0;
        std::printf("%-8s %10.1f %10.1f %10llu %10.1f MB %12.3f\n", m.name, 100.0 * cpu / wall,
                    static_cast<double>(raw) / 1e6 / wall,
                    static_cast<unsigned long long>(st.dropped()),
                    static_cast<double>(st.peak_queued_bytes) / 1e6,
                    static_cast<double>(st.writer.file_bytes) / static_cast<double>(raw));
        if (st.failed) {
            std::printf("  failed: %s\n  file holds %llu scans, %llu dropped after the failure\n",
                        st.error.c_str(), static_cast<unsigned long long>(st.writer.messages),
                        static_cast<unsigned long long>(st.dropped_after_failure));
        }
    }
    fs::remove(path);
    return 0;
}
