#pragma once
// A trajectory file written as poses arrive (KITTI or TUM format), flushed on demand.
#include <Eigen/Geometry>
#include <cstdio>
#include <string>

#include "common/core/trajectory_io.hpp"

namespace ltm::sinks {

enum class TrajectoryFormat { kKitti, kTum };

class TrajectoryFile {
  public:
    // Creates (truncates) the file. Throws common::IoError.
    TrajectoryFile(std::string path, TrajectoryFormat format);
    ~TrajectoryFile();
    TrajectoryFile(const TrajectoryFile&) = delete;
    TrajectoryFile& operator=(const TrajectoryFile&) = delete;

    void append(double stamp, const Eigen::Isometry3d& pose);
    // Replaces the whole content (a corrected trajectory), atomically.
    void rewrite(const common::Trajectory& trajectory);
    void flush();
    std::size_t size() const { return count_; }
    const std::string& path() const { return path_; }

  private:
    std::string path_;
    TrajectoryFormat format_;
    std::FILE* file_ = nullptr;
    std::size_t count_ = 0;
};

}  // namespace ltm::sinks
