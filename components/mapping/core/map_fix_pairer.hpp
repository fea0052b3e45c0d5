#pragma once
// Pairs the Mapper's keyframes with the localisation's poses of the same scans
// (Mapper::add_map_fix): a keyframe, the localisation's state of its scan and its pose arrive in
// any order, from two components. A pose is a fix only while the localisation is tracking the map
// (registered to it this scan) and has been for `min_tracking_run` scans in a row: a first fix
// after a global localisation can be metres off for a few scans. Bounded: the newest `keep` of each
// kind wait.
#include <Eigen/Geometry>
#include <cstdint>
#include <map>
#include <optional>

namespace ltm::mapping {

struct FixKeyframe {
    std::uint64_t local_map_id = 0;
    Eigen::Isometry3d T_anchor_lidar = Eigen::Isometry3d::Identity();
    std::uint32_t index = 0;  // the Mapper's keyframe index
    EIGEN_MAKE_ALIGNED_OPERATOR_NEW
};

struct PairedFix {
    FixKeyframe keyframe;
    Eigen::Isometry3d T_world_lidar = Eigen::Isometry3d::Identity();
    EIGEN_MAKE_ALIGNED_OPERATOR_NEW
};

class MapFixPairer {
  public:
    explicit MapFixPairer(int min_tracking_run = 3, std::size_t keep = 256)
        : min_run_(min_tracking_run), keep_(keep) {}

    // Each returns the fix it completes, if any. Stamps in seconds (of the scan).
    std::optional<PairedFix> keyframe(double stamp, const FixKeyframe& keyframe);
    // The localisation's state of a scan, in scan order: tracking the map or not.
    std::optional<PairedFix> state(double stamp, bool tracking);
    std::optional<PairedFix> pose(double stamp, const Eigen::Isometry3d& T_world_lidar);

  private:
    using Key = std::int64_t;  // nanoseconds
    static Key key(double stamp);
    std::optional<PairedFix> match(Key k);
    template <class Map>
    void bound(Map& m) const {
        while (m.size() > keep_) m.erase(m.begin());
    }

    int min_run_;
    std::size_t keep_;
    int run_ = 0;  // tracking states in a row
    std::map<Key, FixKeyframe> keyframes_;
    std::map<Key, bool> usable_;  // tracking long enough at that scan
    std::map<Key, Eigen::Isometry3d> poses_;
};

}  // namespace ltm::mapping
