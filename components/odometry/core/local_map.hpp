#pragma once
// A local map M_k = {T_k, B_k, V_k} (METHOD.md Eq. 1, 2, 9): the anchor pose, an axis-aligned box
// around the anchor, and the occupied voxels with running statistics (a VoxelGrid), plus an
// optional coarse grid (a multiple of the voxel size) that widens the registration's basin.
//
// Frames: the map frame is the odometry frame shifted to `origin()` (the anchor position snapped to
// the coarse voxel lattice), so every local map shares one voxel lattice and voxels of overlapping
// maps line up exactly. Voxel centres and all point arguments below are in the map frame.
#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <vector>

#include "odometry/core/odometry_config.hpp"
#include "registration/core/voxel_grid.hpp"

namespace ltm::odometry {

class LocalMap {
  public:
    // coarse_factor: 0 for no coarse grid, otherwise its voxel size in voxels (an integer >= 2).
    LocalMap(std::uint32_t id, const Eigen::Isometry3d& T_odom_anchor, double voxel_size,
             double half_extent, const VoxelConfig& voxel_config, double stamp,
             int coarse_factor = 0);

    std::uint32_t id() const { return id_; }
    // Odometry segment (common::LocalMapData::segment): set by LocalMapSet after a restart.
    std::uint32_t segment() const { return segment_; }
    void set_segment(std::uint32_t segment) { segment_ = segment; }
    // Sensor pose when the map was created.
    const Eigen::Isometry3d& T_odom_anchor() const { return T_odom_anchor_; }
    // Map frame origin in the odometry frame; the map frame has the odometry frame's axes.
    const Eigen::Vector3d& origin() const { return origin_; }
    Eigen::Isometry3d T_odom_map() const;
    double voxel_size() const { return voxels_.voxel_size(); }
    double half_extent() const { return half_extent_; }
    double created() const { return created_; }          // stamp of creation [s]
    double last_update() const { return last_update_; }  // stamp of the last integration [s]
    std::uint32_t scans_integrated() const { return scans_; }

    // True when p (map frame) is inside the box B_k.
    bool contains(const Eigen::Vector3f& p) const {
        return ((p - box_centre_).cwiseAbs().array() <= float(half_extent_)).all();
    }

    // Absorbs the points (map frame) of a scan taken from `sensor` (map frame) at `stamp` into
    // their voxels (both grids). Points outside the box are ignored. Returns how many points
    // were absorbed.
    std::size_t integrate(const std::vector<Eigen::Vector3f>& points, const Eigen::Vector3f& sensor,
                          double stamp);

    // Copies the voxels of `other` (same voxel sizes) that fall inside this map's box.
    void seed_from(const LocalMap& other);

    // The voxels (V_k), and the coarse grid (null when disabled).
    const registration::VoxelGrid& voxels() const { return voxels_; }
    const registration::VoxelGrid* coarse() const { return coarse_ ? &*coarse_ : nullptr; }
    std::size_t memory_bytes() const;

  private:
    std::uint32_t id_;
    std::uint32_t segment_ = 0;
    Eigen::Isometry3d T_odom_anchor_;
    Eigen::Vector3d origin_;
    Eigen::Vector3f box_centre_;  // the anchor position, map frame
    double half_extent_;
    double created_, last_update_;
    std::uint32_t scans_ = 0;
    registration::VoxelGrid voxels_;
    std::optional<registration::VoxelGrid> coarse_;
};

}  // namespace ltm::odometry
