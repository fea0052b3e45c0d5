#include "simulator/cli/pcd_scan.hpp"

#include <cstdio>
#include <string>
#include <vector>

#include "common/core/io_error.hpp"

namespace ltm::sim::cli {

void write_scan_pcd(const std::string& path, const common::PointCloud& cloud) {
    const bool with_time = cloud.has_time();
    const std::size_t n = cloud.size(), fields = with_time ? 5 : 4;
    const std::string count = std::to_string(n);
    const std::string header =
        std::string("# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\n") +
        (with_time ? "FIELDS x y z intensity t\nSIZE 4 4 4 4 4\nTYPE F F F F F\nCOUNT 1 1 1 1 1\n"
                   : "FIELDS x y z intensity\nSIZE 4 4 4 4\nTYPE F F F F\nCOUNT 1 1 1 1\n") +
        "WIDTH " + count + "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " + count +
        "\nDATA binary\n";
    std::vector<float> raw(n * fields);
    for (std::size_t i = 0; i < n; ++i) {
        float* p = raw.data() + i * fields;
        p[0] = cloud.points[i].x();
        p[1] = cloud.points[i].y();
        p[2] = cloud.points[i].z();
        p[3] = cloud.has_intensity() ? cloud.intensity[i] : 0.0f;
        if (with_time) p[4] = cloud.time[i];
    }
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) throw common::IoError(path, "cannot open for writing");
    bool ok = std::fwrite(header.data(), 1, header.size(), f) == header.size();
    ok = ok && (raw.empty() || std::fwrite(raw.data(), sizeof(float), raw.size(), f) == raw.size());
    if (std::fclose(f) != 0 || !ok) throw common::IoError(path, "write failed");
}

}  // namespace ltm::sim::cli
