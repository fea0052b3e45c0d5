#include "sources/core/scan_folder.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "common/core/io_error.hpp"
#include "common/core/kitti_io.hpp"
#include "common/core/pcl_cloud_io.hpp"

namespace fs = std::filesystem;

namespace ltm::sources {

ScanFolder::ScanFolder(const ScanFolderConfig& config) : config_(config) {
    using common::IoError;
    std::vector<std::string> all;
    std::string seq_dir = config.path;
    if (config_.format == ScanFormat::kAuto)
        config_.format = common::list_kitti_scans(config.path).empty() ? ScanFormat::kCloudFiles
                                                                       : ScanFormat::kKittiBin;
    if (config_.format == ScanFormat::kKittiBin) {
        all = common::list_kitti_scans(config.path);
        seq_dir = common::kitti_sequence_dir(config.path);
        if (all.empty())
            throw IoError(config.path, "no .bin scans (expected DIR/velodyne/*.bin or DIR/*.bin)");
    } else {
        if (!fs::is_directory(config.path)) throw IoError(config.path, "not a folder");
        fs::path dir(config.path);
        if (fs::is_directory(dir / "Scans")) dir /= "Scans";  // FAST-LIO / SC-A-LOAM exports
        for (const auto& e : fs::directory_iterator(dir))
            if (e.is_regular_file() && common::is_cloud_file(e.path().string()))
                all.push_back(e.path().string());
        std::sort(all.begin(), all.end());
        if (all.empty()) throw IoError(config.path, "no .pcd or .ply files");
    }
    // Times and poses cover the whole folder; the window is applied afterwards.
    std::vector<double> times;
    std::string times_file = config.times_file;
    if (times_file.empty() && fs::is_regular_file(fs::path(seq_dir) / "times.txt"))
        times_file = (fs::path(seq_dir) / "times.txt").string();
    if (!times_file.empty()) {
        times = common::read_times(times_file);
        has_times_ = true;
        if (times.size() < all.size())
            throw IoError(times_file, std::to_string(times.size()) + " times for " +
                                          std::to_string(all.size()) + " scans");
    } else {
        for (std::size_t i = 0; i < all.size(); ++i) times.push_back(i * config.default_period_s);
    }
    common::PoseList poses;
    if (!config.poses_file.empty()) {
        poses = common::read_kitti_poses(config.poses_file);
        if (poses.size() < all.size())
            throw IoError(config.poses_file, std::to_string(poses.size()) + " poses for " +
                                                 std::to_string(all.size()) + " scans");
    }
    if (config.start >= all.size())
        throw IoError(config.path, "start " + std::to_string(config.start) +
                                       " is past the last scan (" + std::to_string(all.size()) +
                                       " scans)");
    const std::size_t end =
        config.count ? std::min(all.size(), config.start + config.count) : all.size();
    for (std::size_t i = config.start; i < end; ++i) {
        files_.push_back(all[i]);
        times_.push_back(times[i]);
        if (!poses.empty()) poses_.push_back(poses[i]);
    }
    for (std::size_t i = 1; i < times_.size(); ++i)
        if (times_[i] < times_[i - 1])
            throw IoError(times_file,
                          "time goes backwards at scan " + std::to_string(config.start + i));
}

common::PointCloud ScanFolder::load(std::size_t i) const {
    common::PointCloud cloud = config_.format == ScanFormat::kKittiBin
                                   ? common::read_kitti_bin(files_[i])
                                   : common::load_cloud_file(files_[i], times_[i]);
    cloud.stamp = times_[i];
    check_point_times(cloud, files_[i]);
    return cloud;
}

void check_point_times(const common::PointCloud& cloud, const std::string& file) {
    float worst = 0.0f;
    for (const float t : cloud.time) {
        if (!std::isfinite(t)) throw common::IoError(file, "a per-point time is not finite");
        worst = std::max(worst, std::abs(t));
    }
    if (worst <= kMaxPointTime) return;
    char what[200];
    std::snprintf(what, sizeof what,
                  "per-point times reach %.6g s from the scan stamp (at most %g s expected: "
                  "seconds after it, nanoseconds in integer fields, or absolute times that "
                  "match times.txt)",
                  static_cast<double>(worst), static_cast<double>(kMaxPointTime));
    throw common::IoError(file, what);
}

}  // namespace ltm::sources
