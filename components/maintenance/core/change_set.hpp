#pragma once
// What one maintenance pass changed (mirrors ltm_msgs/MapChangeSet): segments removed (moving or
// vanished) and segments added (new objects seen in every recent view), each with its voxels.
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

namespace ltm::maintenance {

enum class ChangeReason : std::uint8_t { kMoving = 0, kVanished = 1, kNew = 2 };
const char* reason_name(ChangeReason reason);  // "moving", "vanished", "new"

struct SegmentChange {
    std::uint64_t id = 0;  // unique within the map's maintenance history
    ChangeReason reason = ChangeReason::kMoving;
    bool removed() const { return reason != ChangeReason::kNew; }
    Eigen::Vector2i region = Eigen::Vector2i::Zero();
    Eigen::Vector3f centroid = Eigen::Vector3f::Zero();  // world frame [m]
    Eigen::Vector3f bbox_min = Eigen::Vector3f::Zero(), bbox_max = Eigen::Vector3f::Zero();
    double first_seen = 0.0, last_seen = 0.0;  // map time of its first and last point [s]
    double score = 0.0;                        // mean normalised W1 of its judged voxels
    std::uint32_t judged = 0;                  // voxels with enough views to judge
    std::vector<Eigen::Vector3f> voxels;       // centres of the voxels removed or added
};

struct ChangeSet {
    std::uint32_t session = 0;
    double map_time = 0.0;  // [s] when the pass ran
    float voxel_size = 0.0f;
    std::vector<SegmentChange> changes;
    std::size_t voxels_before = 0, voxels_removed = 0, voxels_judged = 0;
    std::size_t segments = 0, ground_voxels = 0;
    double time_ms = 0.0;

    std::size_t count(ChangeReason reason) const;
    std::size_t removed_voxels_by(ChangeReason reason) const;
    void append(const ChangeSet& other);  // the changes of another pass (e.g. region)
};

}  // namespace ltm::maintenance
