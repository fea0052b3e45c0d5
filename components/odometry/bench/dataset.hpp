#pragma once
// The scans of a benchmark folder: KITTI layout (DIR/velodyne/*.bin or DIR/*.bin, times.txt in
// the sequence folder) or a PCD/PLY folder (DIR/Scans/*.pcd, DIR/*.pcd or *.ply, times.txt in DIR).
#include <string>
#include <vector>

#include "common/core/point_cloud.hpp"

namespace ltm::odometry::bench {

class Dataset {
  public:
    // Throws common::IoError when the folder holds no scans or its times.txt is unusable.
    explicit Dataset(const std::string& dir);

    std::size_t size() const { return files_.size(); }
    const std::string& kind() const { return kind_; }             // "kitti" or "pcd"
    const std::string& sequence_dir() const { return seq_dir_; }  // where times.txt etc. live
    bool has_times() const { return !times_.empty(); }
    // Scan i with its stamp (times.txt, or i * 0.1 s without one). Throws common::IoError.
    common::PointCloud load(std::size_t i) const;

  private:
    std::string kind_, seq_dir_;
    std::vector<std::string> files_;
    std::vector<double> times_;
};

}  // namespace ltm::odometry::bench
