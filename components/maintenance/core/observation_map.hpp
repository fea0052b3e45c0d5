#pragma once
// The voxels of one maintenance region with their observation history (METHOD.md section 5): per
// voxel the sums of its points (centre, normal), its creation and last-hit map time, and its view
// history: per time slot, the views that saw it (a return at it: "hit") and the views that saw
// through it (a return beyond it: "free"). Together they are the voxel's time distributions of
// Eq. 14: hits D_s, views in which it was actually in view D_M = hits + free.
// Compact (84 bytes a voxel and a 4-byte index bucket at a load of 0.5 to 0.8): point sums in
// fixed point (point_sums.hpp), times in ticks, the history in fixed entries (voxel_history.hpp).
//
// Points only create voxels and shape them; what a view says is recorded by judge(), once per view
// and voxel, so every voxel's hits and free times come from the same views.
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "maintenance/core/maintenance_config.hpp"
#include "maintenance/core/point_sums.hpp"
#include "maintenance/core/range_image.hpp"
#include "maintenance/core/time_distribution.hpp"
#include "maintenance/core/voxel_history.hpp"
#include "maintenance/core/voxel_index.hpp"
#include "registration/core/voxel.hpp"

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

// kMoving: a point of an object the motion tracker saw move landed in it (motion_tracker.hpp).
enum VoxelFlags : std::uint8_t { kGround = 1, kNew = 2, kMoving = 4 };

// Map times of a voxel are kept in ticks of 1/16 s (uint32: 8.5 years of map time); a session
// starts on a tick (LongTermMap), so "created before this session" is exact.
constexpr double kTicksPerSecond = 16.0;
std::uint32_t to_ticks(double map_time);  // floor, clamped to the uint32 range
inline double from_ticks(std::uint32_t ticks) { return double(ticks) / kTicksPerSecond; }

// A voxel of the maintained map, 84 bytes (memory and README: components/maintenance/README.md).
struct ObservedVoxel {
    registration::VoxelKey key() const { return (std::uint64_t(key_hi) << 32) | key_lo; }
    void set_key(registration::VoxelKey k) {
        key_lo = std::uint32_t(k);
        key_hi = std::uint32_t(k >> 32);
    }
    double created() const { return from_ticks(created_ticks); }        // first point [s]
    double last_point() const { return from_ticks(last_point_ticks); }  // last point [s]
    registration::VoxelSums sums(float voxel_size) const { return points.sums(voxel_size); }
    SlotHistogram hit_histogram() const { return history.hit_histogram(); }
    SlotHistogram free_histogram() const { return history.free_histogram(); }

    std::uint32_t key_lo = 0, key_hi = 0;
    std::uint32_t created_ticks = 0, last_point_ticks = 0;  // map time of the first/last point
    std::uint32_t segment = 0;  // after maintenance: 0 ground or none, else the segment id
    PointSums points;           // relative to the cell's centre
    std::uint8_t flags = 0;
    VoxelHistory history;  // views that hit it and that saw through it
};

struct JudgeCounts {
    std::size_t voxels = 0, hit = 0, free = 0, occluded = 0, unseen = 0;
};

class ObservationMap {
  public:
    // Voxels on the lattice of edge voxel_size in the world frame (shared by every region).
    ObservationMap(const MaintenanceConfig& config, const Eigen::Vector2i& region);

    const Eigen::Vector2i& region() const { return region_; }
    std::size_t size() const { return voxels_.size(); }
    bool empty() const { return voxels_.empty(); }

    // Points (world frame) of a scan at `map_time`: their voxels are created or updated.
    // With established_before >= 0 (map time), a point in an empty cell next to a voxel created
    // before then (one of the 26 neighbouring cells of this region) is dropped: a surface the map
    // has, seen again a little across a cell face or between an earlier session's rings. Cells
    // with no such neighbour are created (a new object, new ground).
    void add_points(const std::vector<Eigen::Vector3f>& points, double map_time,
                    double established_before = -1.0);

    // What `view` says about every voxel within max_range of its sensor: a hit or a free time
    // in the voxel's histories (nothing when occluded or unseen).
    JudgeCounts judge(const View& view);

    // The voxel holding p (world frame), or kNone.
    std::uint32_t find(const Eigen::Vector3f& p) const;
    static constexpr std::uint32_t kNone = VoxelIndex::kNone;

    registration::VoxelKey key(std::uint32_t i) const { return voxels_[i].key(); }
    Eigen::Vector3f cell_centre(std::uint32_t i) const;
    Eigen::Vector3f centre(std::uint32_t i) const;  // mean of its points
    // Unit normal of its points (smallest eigenvector), or zero when it has fewer than 3 points
    // or no plane-like spread.
    Eigen::Vector3f normal(std::uint32_t i) const;
    const ObservedVoxel& voxel(std::uint32_t i) const { return voxels_[i]; }
    ObservedVoxel& voxel(std::uint32_t i) { return voxels_[i]; }
    float voxel_size() const { return voxel_size_; }

    // Room for n voxels in all (the map file reader knows a region's count).
    void reserve(std::size_t n);
    // Puts a voxel back as it was saved (the map file reader); false when its key is taken.
    bool restore(const ObservedVoxel& voxel);

    // Drops the voxels with remove[i] true (the index is rebuilt).
    void erase(const std::vector<bool>& remove);
    // The voxels and their index (capacity included).
    std::size_t memory_bytes() const;

  private:
    std::uint32_t insert(registration::VoxelKey key, double map_time);
    void append(const ObservedVoxel& voxel);  // grows by 1/16 at a time, not 2x

    MaintenanceConfig config_;
    Eigen::Vector2i region_;
    float voxel_size_, inv_voxel_size_;
    VoxelIndex index_;
    std::vector<ObservedVoxel> voxels_;
};

}  // namespace ltm::maintenance
