#pragma once
// The voxels of one maintenance region with their observation history (METHOD.md section 5): per
// voxel the running sums of its points (centre, normal), its creation and last-hit map time, and
// two slot histograms: the times a view saw it (a return at it: "hit") and the times a view saw
// through it (a return beyond it: "free"). Together they are the voxel's time distributions of
// Eq. 14: hits D_s, views in which it was actually in view D_M = hits + free.
//
// Points only create voxels and shape them; what a view says is recorded by judge(), once per view
// and voxel, so every voxel's hits and free times come from the same views.
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "maintenance/core/maintenance_config.hpp"
#include "maintenance/core/range_image.hpp"
#include "maintenance/core/time_distribution.hpp"
#include "registration/core/voxel.hpp"
#include "registration/core/voxel_hash.hpp"

namespace ltm::maintenance {

// A scan as a judge of the map: its range image, where it was taken and when.
struct View {
    std::uint64_t id = 0;
    std::uint32_t session = 0;
    double map_time = 0.0;  // [s]
    Eigen::Isometry3d T_world_sensor = Eigen::Isometry3d::Identity();
    RangeImage image;
    EIGEN_MAKE_ALIGNED_OPERATOR_NEW
};

enum VoxelFlags : std::uint8_t { kGround = 1, kNew = 2 };

struct ObservedVoxel {
    registration::VoxelSums sums;  // relative to the cell's centre
    double created = 0.0;          // map time of the first point [s]
    double last_point = 0.0;       // map time of the last point [s]
    std::uint32_t session = 0;     // session of the first point
    SlotHistogram hits, free;
    std::uint32_t segment = 0;  // after maintenance: 0 ground or none, else the segment id
    std::uint8_t flags = 0;
};

struct JudgeCounts {
    std::size_t voxels = 0, hit = 0, free = 0, occluded = 0, unseen = 0;
};

class ObservationMap {
  public:
    // Voxels on the lattice of edge voxel_size in the world frame (shared by every region).
    ObservationMap(const MaintenanceConfig& config, const Eigen::Vector2i& region);

    const Eigen::Vector2i& region() const { return region_; }
    std::size_t size() const { return keys_.size(); }
    bool empty() const { return keys_.empty(); }

    // Points (world frame) of a scan at `map_time`: their voxels are created or updated.
    void add_points(const std::vector<Eigen::Vector3f>& points, double map_time,
                    std::uint32_t session);

    // What `view` says about every voxel within max_range of its sensor: a hit or a free time
    // in the voxel's histories (nothing when occluded or unseen).
    JudgeCounts judge(const View& view);

    // The voxel holding p (world frame), or kNone.
    std::uint32_t find(const Eigen::Vector3f& p) const;
    static constexpr std::uint32_t kNone = registration::VoxelHash::kNone;

    registration::VoxelKey key(std::uint32_t i) const { return keys_[i]; }
    Eigen::Vector3f cell_centre(std::uint32_t i) const;
    Eigen::Vector3f centre(std::uint32_t i) const;  // mean of its points
    // Unit normal of its points (smallest eigenvector), or zero when it has fewer than 3 points
    // or no plane-like spread.
    Eigen::Vector3f normal(std::uint32_t i) const;
    const ObservedVoxel& voxel(std::uint32_t i) const { return voxels_[i]; }
    ObservedVoxel& voxel(std::uint32_t i) { return voxels_[i]; }
    float voxel_size() const { return voxel_size_; }

    // Puts a voxel back as it was saved (the map file reader); false when the key is taken.
    bool restore(registration::VoxelKey key, ObservedVoxel voxel);

    // Drops the voxels with remove[i] true (the hash is rebuilt).
    void erase(const std::vector<bool>& remove);
    std::size_t memory_bytes() const;

  private:
    std::uint32_t insert(registration::VoxelKey key, double map_time, std::uint32_t session);

    MaintenanceConfig config_;
    Eigen::Vector2i region_;
    float voxel_size_, inv_voxel_size_;
    registration::VoxelHash hash_;
    std::vector<registration::VoxelKey> keys_;
    std::vector<ObservedVoxel> voxels_;
    std::vector<std::uint64_t> last_scan_;  // internal: the add_points pass that touched it
    std::uint64_t pass_ = 0;
};

}  // namespace ltm::maintenance
