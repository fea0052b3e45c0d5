#pragma once
// A folder of recorded scans: KITTI layout (velodyne/*.bin, times.txt, optional poses) or PCD/PLY
// files (optional times.txt and KITTI-format poses file). Scans load one at a time.
// PCD/PLY scans keep their per-point time (PointCloud::time, seconds after the scan stamp) when
// they have a field t, time, timestamp or offset_time: floating fields are seconds, integer ones
// nanoseconds (Ouster `t`, Livox `offset_time`); absolute times (over 1e6 s) are made relative
// to the scan's stamp from times.txt.
#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "common/core/point_cloud.hpp"
#include "common/core/trajectory_io.hpp"

namespace ltm::sources {

enum class ScanFormat {
    kKittiBin,    // DIR/velodyne/*.bin or DIR/*.bin
    kCloudFiles,  // DIR/Scans/*.pcd|ply or DIR/*.pcd|ply
    kAuto,        // KITTI when the folder has .bin scans, else cloud files
};

struct ScanFolderConfig {
    std::string path;  // the folder (KITTI: the sequence or its velodyne/)
    ScanFormat format = ScanFormat::kKittiBin;
    std::string times_file;         // "" : <sequence>/times.txt when present
    std::string poses_file;         // "" : none (KITTI format, one line a scan)
    double default_period_s = 0.1;  // scan spacing when there is no times file
    std::size_t start = 0;          // first scan
    std::size_t count = 0;          // 0: all from start
};

// Per-point times further than this from their scan's stamp are not relative seconds [s].
constexpr float kMaxPointTime = 10.0f;

// Throws common::IoError naming `file` when a per-point time is not finite or further than
// kMaxPointTime from the stamp (wrong units, or absolute times that do not match times.txt).
void check_point_times(const common::PointCloud& cloud, const std::string& file);

class ScanFolder {
  public:
    // Throws common::IoError (one line) when the folder, times or poses are missing or malformed,
    // or when they disagree with the number of scans.
    explicit ScanFolder(const ScanFolderConfig& config);

    std::size_t size() const { return files_.size(); }
    ScanFormat format() const { return config_.format; }  // resolved (never kAuto)
    bool has_times() const { return has_times_; }         // false: default_period_s spacing
    double stamp(std::size_t i) const { return times_[i]; }
    bool has_poses() const { return !poses_.empty(); }
    const Eigen::Isometry3d& pose(std::size_t i) const { return poses_[i]; }
    const std::string& file(std::size_t i) const { return files_[i]; }
    // Loads scan i with its stamp (and per-point times when the file has them). Throws
    // common::IoError for a damaged file or implausible per-point times.
    common::PointCloud load(std::size_t i) const;

  private:
    ScanFolderConfig config_;
    std::vector<std::string> files_;
    std::vector<double> times_;
    common::PoseList poses_;
    bool has_times_ = false;
};

}  // namespace ltm::sources
