#pragma once
// The map as one cloud Foxglove can draw: the voxel centres of every local map the odometry
// published, placed by the pose graph's optimised anchors (the map frame; the odometry frame
// until a pose graph arrives), decimated on a voxel grid to at most `max_points`. No DDS: the
// component feeds it the local maps and the graph and sends what build() returns.
#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <map>
#include <vector>

namespace ltm::bridge {

struct MapCloudConfig {
    std::size_t max_points = 200000;  // the cloud sent never has more
    double leaf_m = 0.5;              // decimation grid [m]; coarser when the map needs it
    // The local maps' points kept at most (0: 4 x max_points): past it every kept local map is
    // decimated on a coarser grid (from leaf_m, a quarter coarser each time), and so are later
    // ones. A robot's day adds local maps with its distance (a lap of a known route too): the
    // points kept (12 B each) stay bounded, the view coarsens (issue 28).
    std::size_t max_kept_points = 0;
};

// The centroid of the points in each cell of a `leaf_m` grid, growing the leaf until at most
// `max_points` cells remain; `leaf_m` is set to the leaf used. Keeps its table between calls.
class VoxelDecimator {
  public:
    std::vector<Eigen::Vector3f> decimate(const std::vector<Eigen::Vector3f>& points,
                                          std::size_t max_points, double& leaf_m);

  private:
    struct Cell {
        std::uint64_t key = 0;  // 0: empty
        std::uint32_t count = 0;
        Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    };
    std::vector<Cell> cells_;
};

// The same with a table of its own.
std::vector<Eigen::Vector3f> decimate(const std::vector<Eigen::Vector3f>& points,
                                      std::size_t max_points, double& leaf_m);

class MapCloud {
  public:
    explicit MapCloud(MapCloudConfig config = {}) : config_(config) {}

    // A local map's newest snapshot: its anchor in the odometry frame and its points in the
    // anchor frame (replaces an earlier snapshot of the same id).
    void set_local_map(std::uint64_t id, const Eigen::Isometry3d& T_odom_anchor,
                       std::vector<Eigen::Vector3f> points_anchor);
    // The pose graph's anchors T_map_anchor (replaces the earlier graph).
    void set_graph(std::map<std::uint64_t, Eigen::Isometry3d> T_map_anchor);

    // Something changed since the last build().
    bool dirty() const { return dirty_; }
    std::size_t local_maps() const { return maps_.size(); }
    std::size_t kept_points() const { return kept_; }
    double kept_leaf_m() const { return kept_leaf_; }  // 0: kept as they came
    std::size_t memory_bytes() const;

    struct Cloud {
        std::vector<Eigen::Vector3f> points;  // <= max_points
        bool in_map_frame = false;            // false: the odometry frame (no graph yet)
        double leaf_m = 0;                    // the grid it was decimated on
        std::size_t input_points = 0;         // before decimation
    };
    Cloud build();

  private:
    struct LocalMap {
        Eigen::Isometry3d T_odom_anchor = Eigen::Isometry3d::Identity();
        std::vector<Eigen::Vector3f> points;
    };
    // T_map_odom from the newest local map the graph holds (for local maps it has not placed).
    Eigen::Isometry3d map_from_odom() const;
    // Coarsens the kept local maps until at most max_kept_points are kept.
    void bound();

    MapCloudConfig config_;
    std::map<std::uint64_t, LocalMap> maps_;
    std::map<std::uint64_t, Eigen::Isometry3d> graph_;
    bool dirty_ = false;
    std::size_t kept_ = 0;    // points in maps_
    double kept_leaf_ = 0.0;  // the grid the kept maps are decimated on (0: none)
    VoxelDecimator decimator_;
};

}  // namespace ltm::bridge
