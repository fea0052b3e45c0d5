#include "odometry/bench/dataset.hpp"

#include <algorithm>
#include <filesystem>

#include "common/core/io_error.hpp"
#include "common/core/kitti_io.hpp"
#include "common/core/pcl_cloud_io.hpp"

namespace ltm::odometry::bench {
namespace fs = std::filesystem;

namespace {

std::vector<std::string> cloud_files(const fs::path& dir) {
    std::vector<std::string> files;
    for (const auto& e : fs::directory_iterator(dir)) {
        if (e.is_regular_file() && common::is_cloud_file(e.path().string())) {
            files.push_back(e.path().string());
        }
    }
    std::sort(files.begin(), files.end());
    return files;
}

}  // namespace

Dataset::Dataset(const std::string& dir) {
    if (!fs::is_directory(dir)) throw common::IoError(dir, "not a folder");
    files_ = common::list_kitti_scans(dir);
    if (!files_.empty()) {
        kind_ = "kitti";
        seq_dir_ = common::kitti_sequence_dir(dir);
    } else {
        kind_ = "pcd";
        seq_dir_ = dir;
        const fs::path scans = fs::path(dir) / "Scans";
        files_ = cloud_files(fs::is_directory(scans) ? scans : fs::path(dir));
    }
    if (files_.empty()) {
        throw common::IoError(dir,
                              "no scans (.bin in velodyne/ or here, .pcd/.ply in Scans/ or here)");
    }
    const fs::path times = fs::path(seq_dir_) / "times.txt";
    if (fs::exists(times)) {
        times_ = common::read_times(times.string());
        if (times_.size() < files_.size()) {
            throw common::IoError(times.string(), std::to_string(times_.size()) + " times for " +
                                                      std::to_string(files_.size()) + " scans");
        }
    }
}

common::PointCloud Dataset::load(std::size_t i) const {
    common::PointCloud cloud =
        kind_ == "kitti" ? common::read_kitti_bin(files_[i]) : common::load_cloud_file(files_[i]);
    cloud.stamp = times_.empty() ? 0.1 * double(i) : times_[i];
    return cloud;
}

}  // namespace ltm::odometry::bench
