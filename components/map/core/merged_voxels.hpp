#pragma once
// The voxels of every local map of a map merged into one voxel map in the map frame (what
// localisation tracks against and global localisation verifies against): each local map's voxels
// are carried by their anchor's optimised pose (T_world_anchor * T_anchor_grid) onto one lattice
// of the largest local-map voxel size. Where local maps overlap, a cell keeps the voxel of the
// local map anchored nearest to it (built while the sensor was closest), so neighbouring cells
// come from the same local map, whose surfaces agree with each other.
#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <unordered_map>
#include <vector>

#include "common/core/local_map_data.hpp"
#include "map/core/map_data.hpp"

namespace ltm::map {

struct MergedVoxelsFilter {
    double min_health = 0.0;     // voxels below this health are left out [0..1]
    double min_planarity = 0.4;  // voxels below this planarity are left out (no usable plane)
};

struct MergedVoxels {
    // Map frame (grid frame = map frame, T_anchor_grid = I), finished; the life records keep no
    // observation indices and a voxel's stability is weighted by its health.
    std::shared_ptr<common::LocalMapData> voxels;
    std::size_t local_maps = 0;  // local maps merged (those placed in the graph)
    std::size_t sessions = 0;    // sessions they came from
};

// A voxel is kept when it has points, a unit normal, a finite centre and passes the filter.
bool merges(const common::VoxelData& v, const MergedVoxelsFilter& filter);
MergedVoxels merge_voxels(const MapData& map, const MergedVoxelsFilter& filter);

// The same merge fed one local map at a time (a paged map reads them one by one, each freed once
// added): local maps added in merge_voxels' order (the map's, by node) with the lattice it would
// use (the largest of their voxel sizes) give its result voxel for voxel.
class VoxelMerger {
  public:
    VoxelMerger(float voxel_size, const MergedVoxelsFilter& filter);
    void add(const StoredLocalMap& local_map, const Eigen::Isometry3d& T_world_anchor);
    MergedVoxels finish();

  private:
    MergedVoxelsFilter filter_;
    float inv_ = 1.0f;
    MergedVoxels out_;
    // Packed cell -> merged voxel index: open addressing with linear probing (a whole map's
    // merge looks up every voxel of every local map; a node-based map spent most of the merge
    // allocating), grown to keep it at most half full.
    std::uint32_t* slot(std::uint64_t key, bool* fresh);
    void grow();
    std::vector<std::uint64_t> slot_keys_;
    std::vector<std::uint32_t> slot_values_;
    std::size_t slot_count_ = 0;
    std::vector<float> anchor_distance_;  // per merged voxel
    std::vector<std::uint32_t> sessions_;
    Eigen::Vector3d lo_ = Eigen::Vector3d::Constant(1e300), hi_ = -lo_;
};

}  // namespace ltm::map
