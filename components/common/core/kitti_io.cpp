#include "common/core/kitti_io.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/core/io_error.hpp"

namespace fs = std::filesystem;

namespace ltm::common {

PointCloud read_kitti_bin(const std::string& path) {
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) throw IoError(path, "cannot open");
    std::fseek(f, 0, SEEK_END);
    const long bytes = std::ftell(f);
    std::fseek(f, 0, SEEK_SET);
    if (bytes < 0 || bytes % 16 != 0) {
        std::fclose(f);
        throw IoError(path, "size " + std::to_string(bytes) +
                                " bytes is not a multiple of 16 (float32 x y z intensity)");
    }
    const std::size_t n = static_cast<std::size_t>(bytes) / 16;
    std::vector<float> raw(n * 4);
    const std::size_t got = n ? std::fread(raw.data(), 16, n, f) : 0;
    std::fclose(f);
    if (got != n) throw IoError(path, "short read");
    PointCloud cloud;
    cloud.points.resize(n);
    cloud.intensity.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        cloud.points[i] = Eigen::Vector3f(raw[4 * i], raw[4 * i + 1], raw[4 * i + 2]);
        cloud.intensity[i] = raw[4 * i + 3];
    }
    return cloud;
}

void write_kitti_bin(const std::string& path, const PointCloud& cloud) {
    std::vector<float> raw(cloud.size() * 4);
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        raw[4 * i] = cloud.points[i].x();
        raw[4 * i + 1] = cloud.points[i].y();
        raw[4 * i + 2] = cloud.points[i].z();
        raw[4 * i + 3] = cloud.has_intensity() ? cloud.intensity[i] : 0.0f;
    }
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) throw IoError(path, "cannot open for writing");
    const bool ok =
        raw.empty() || std::fwrite(raw.data(), sizeof(float), raw.size(), f) == raw.size();
    if (std::fclose(f) != 0 || !ok) throw IoError(path, "write failed");
}

std::vector<std::string> list_kitti_scans(const std::string& dir) {
    fs::path root(dir);
    if (!fs::is_directory(root)) throw IoError(dir, "not a folder");
    if (fs::is_directory(root / "velodyne")) root /= "velodyne";
    std::vector<std::string> files;
    for (const auto& e : fs::directory_iterator(root)) {
        if (e.is_regular_file() && e.path().extension() == ".bin")
            files.push_back(e.path().string());
    }
    std::sort(files.begin(), files.end());
    return files;
}

std::string kitti_sequence_dir(const std::string& dir) {
    fs::path root(dir);
    if (root.filename() == "velodyne" ||
        (!fs::is_directory(root / "velodyne") && fs::exists(root.parent_path() / "times.txt") &&
         !fs::exists(root / "times.txt"))) {
        return root.parent_path().string();
    }
    return root.string();
}

std::vector<double> read_times(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw IoError(path, "cannot open");
    std::vector<double> times;
    std::string line;
    int lineno = 0;
    while (std::getline(in, line)) {
        ++lineno;
        if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
        std::istringstream ss(line);
        double t;
        if (!(ss >> t)) throw IoError(path, "line " + std::to_string(lineno) + ": not a time");
        times.push_back(t);
    }
    return times;
}

void write_times(const std::string& path, const std::vector<double>& times) {
    std::ofstream out(path);
    if (!out) throw IoError(path, "cannot open for writing");
    char buf[64];
    for (double t : times) {
        std::snprintf(buf, sizeof buf, "%.6e\n", t);
        out << buf;
    }
    if (!out.flush()) throw IoError(path, "write failed");
}

Eigen::Isometry3d read_kitti_calib_tr(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw IoError(path, "cannot open");
    std::string line;
    while (std::getline(in, line)) {
        if (line.rfind("Tr:", 0) != 0) continue;
        std::istringstream ss(line.substr(3));
        Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 4; ++c)
                if (!(ss >> T.matrix()(r, c))) throw IoError(path, "Tr: needs 12 numbers");
        return T;
    }
    return Eigen::Isometry3d::Identity();
}

}  // namespace ltm::common
