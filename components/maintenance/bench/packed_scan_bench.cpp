// ltm_bench_packed_scan SCAN.bin...: how small and how fast the maintenance's packed scans are
// (maintenance/core/packed_scan.hpp) on KITTI-layout scans (float32 x y z intensity a point; the
// intensity is not packed, the maintenance does not keep it): points, bytes before and after,
// the ratio, pack and unpack time (median of 20) and whether every bit came back.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "maintenance/core/packed_scan.hpp"

namespace {

using Clock = std::chrono::steady_clock;
constexpr int kRepeats = 20;

bool read_kitti(const std::string& path, std::vector<Eigen::Vector3f>& points) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return false;
    float x[4];
    while (in.read(reinterpret_cast<char*>(x), sizeof x)) points.emplace_back(x[0], x[1], x[2]);
    return true;
}

double median_ms(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2 || std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h") {
        std::printf(
            "Usage: ltm_bench_packed_scan [--level L] SCAN.bin...\n"
            "The maintenance's packed scans on KITTI-layout scans: size, ratio, pack and unpack "
            "time, bit-exact check.\n");
        return argc < 2 ? 2 : 0;
    }
    int level = 1, first = 1;
    if (std::string(argv[1]) == "--level" && argc >= 3) {
        level = std::atoi(argv[2]);
        first = 3;
    }
    std::size_t total_in = 0, total_out = 0;
    std::printf("%-60s %8s %10s %10s %6s %8s %8s %s\n", "scan", "points", "bytes", "packed", "%",
                "pack ms", "unpk ms", "exact");
    for (int a = first; a < argc; ++a) {
        std::vector<Eigen::Vector3f> points;
        if (!read_kitti(argv[a], points)) {
            std::fprintf(stderr, "ltm_bench_packed_scan: %s: cannot read\n", argv[a]);
            return 1;
        }
        std::vector<double> pack_ms, unpack_ms;
        ltm::maintenance::PackedScan packed;
        std::vector<Eigen::Vector3f> back;
        try {
            for (int k = 0; k < kRepeats; ++k) {
                const auto t0 = Clock::now();
                packed = ltm::maintenance::pack_points(points, level);
                const auto t1 = Clock::now();
                back = ltm::maintenance::unpack_points(packed);
                const auto t2 = Clock::now();
                pack_ms.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
                unpack_ms.push_back(std::chrono::duration<double, std::milli>(t2 - t1).count());
            }
        } catch (const std::exception& e) {
            std::fprintf(stderr, "ltm_bench_packed_scan: %s: %s\n", argv[a], e.what());
            return 1;
        }
        const std::size_t in = points.size() * sizeof(Eigen::Vector3f);
        const bool exact = back.size() == points.size() &&
                           (points.empty() || std::memcmp(back.data(), points.data(), in) == 0);
        total_in += in;
        total_out += packed.bytes.size();
        std::printf("%-60s %8zu %10zu %10zu %6.1f %8.2f %8.2f %s\n", argv[a], points.size(), in,
                    packed.bytes.size(),
                    in ? 100.0 * double(packed.bytes.size()) / double(in) : 0.0, median_ms(pack_ms),
                    median_ms(unpack_ms), exact ? "yes" : "NO");
        if (!exact) return 1;
    }
    std::printf("all: %zu -> %zu bytes (%.1f %%), zstd level %d\n", total_in, total_out,
                total_in ? 100.0 * double(total_out) / double(total_in) : 0.0, level);
    return 0;
}
