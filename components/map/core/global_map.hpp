#pragma once
// The global voxel map (METHOD.md section 3): the union of the local maps under their optimised
// anchors. Voxel centres and normals are carried to the world frame
// (T_world_anchor * T_anchor_grid); voxels of overlapping maps that land in the same cell of a
// world grid are fused (centres and sign-aligned normals averaged, weighted by point count).
#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "common/core/config_check.hpp"
#include "common/core/local_map_data.hpp"
#include "common/core/ply_io.hpp"

namespace ltm::map {

struct GlobalMapConfig {
    double voxel_size = 0.0;       // fusion grid [m]; 0: the largest local-map voxel size
    bool with_normal_only = true;  // leave out voxels without a normal
    double min_planarity = 0.0;    // leave out voxels below this planarity [0..1]
    int min_point_count = 1;       // leave out voxels with fewer points
};

// Calls v(key, field, rule) for every field, keys under `prefix` ("global_map."); the rule is the
// field's (common/core/config_check.hpp).
template <class Visitor>
void visit_fields(GlobalMapConfig& c, const std::string& prefix, Visitor&& v) {
    using namespace common::rules;
    v(prefix + "voxel_size", c.voxel_size, non_negative);
    v(prefix + "with_normal_only", c.with_normal_only, unchecked);
    v(prefix + "min_planarity", c.min_planarity, unit);
    v(prefix + "min_point_count", c.min_point_count, non_negative);
}

// The first field that breaks its rule (key relative: "voxel_size"); nullopt when valid.
std::optional<common::ConfigProblem> validate(const GlobalMapConfig& config);

struct PlacedLocalMap {
    const common::LocalMapData* map = nullptr;
    Eigen::Isometry3d T_world_anchor = Eigen::Isometry3d::Identity();
    EIGEN_MAKE_ALIGNED_OPERATOR_NEW
};

struct GlobalMapStats {
    std::size_t input_voxels = 0;  // voxels kept by the filters
    std::size_t fused_voxels = 0;  // output points
};

// Points: fused centres (world frame); normals: fused unit normals. Output order: the order in
// which the cells were first met (input order), so the result is deterministic.
common::PlyCloud build_global_map(const std::vector<PlacedLocalMap>& maps,
                                  const GlobalMapConfig& config, GlobalMapStats* stats = nullptr);

// The same one local map at a time (a caller that reads paged-out local maps keeps one in
// memory): add() in the order build_global_map takes them gives its result. `grid` is the fusion
// grid [m]: config.voxel_size, or when 0 the largest local-map voxel size (1 when none).
class GlobalMapBuilder {
  public:
    GlobalMapBuilder(const GlobalMapConfig& config, double grid);
    void add(const common::LocalMapData& map, const Eigen::Isometry3d& T_world_anchor);
    common::PlyCloud finish(GlobalMapStats* stats = nullptr) const;

  private:
    struct Cell {
        double weight = 0.0;
        Eigen::Vector3d sum = Eigen::Vector3d::Zero();
        Eigen::Vector3d normal_sum = Eigen::Vector3d::Zero();
        Eigen::Vector3d reference = Eigen::Vector3d::Zero();  // first normal: sign reference
        bool has_normal = false;
    };
    GlobalMapConfig config_;
    double inv_ = 1.0;
    std::unordered_map<std::uint64_t, std::size_t> index_;  // registration::VoxelKey -> cell
    std::vector<Cell> cells_;
    std::size_t input_voxels_ = 0;
};

}  // namespace ltm::map
