#include "sinks/core/trajectory_file.hpp"

#include <filesystem>

#include "common/core/io_error.hpp"

namespace ltm::sinks {

TrajectoryFile::TrajectoryFile(std::string path, TrajectoryFormat format)
    : path_(std::move(path)), format_(format) {
    file_ = std::fopen(path_.c_str(), "w");
    if (!file_) throw common::IoError(path_, "cannot open for writing");
}

TrajectoryFile::~TrajectoryFile() {
    if (file_) std::fclose(file_);
}

void TrajectoryFile::append(double stamp, const Eigen::Isometry3d& pose) {
    const std::string line = format_ == TrajectoryFormat::kKitti
                                 ? common::format_kitti_pose(pose)
                                 : common::format_tum_pose(stamp, pose);
    if (std::fputs(line.c_str(), file_) < 0) throw common::IoError(path_, "write failed");
    ++count_;
}

void TrajectoryFile::rewrite(const common::Trajectory& trajectory) {
    const std::string tmp = path_ + ".tmp";
    if (format_ == TrajectoryFormat::kKitti) {
        common::PoseList poses;
        for (const auto& sp : trajectory) poses.push_back(sp.pose);
        common::write_kitti_poses(tmp, poses);
    } else {
        common::write_tum_trajectory(tmp, trajectory);
    }
    std::fclose(file_);
    std::filesystem::rename(tmp, path_);
    file_ = std::fopen(path_.c_str(), "a");
    if (!file_) throw common::IoError(path_, "cannot reopen");
    count_ = trajectory.size();
}

void TrajectoryFile::flush() {
    if (std::fflush(file_) != 0) throw common::IoError(path_, "flush failed");
}

}  // namespace ltm::sinks
