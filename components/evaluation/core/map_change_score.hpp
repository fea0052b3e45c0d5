#pragma once
// What a map kept of a site's changes: voxels inside the boxes of removed objects, of moved
// objects' old and new places and of added objects, in the first day's map (what was there) and
// in a later map (what the next day localises on); and how many of the first map's static voxels
// the later map still has.
#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "evaluation/core/site_objects.hpp"

namespace ltm::eval {

struct MapChangeConfig {
    double box_margin = 0.3;     // [m] object boxes grown by this (voxel centres, noise)
    double static_radius = 0.5;  // [m] a first-map voxel is kept when a later voxel is this near
    std::size_t min_voxels = 3;  // an added object is in the map with at least this many voxels
    // [m] voxels lower than this above the ground under an object (SiteObject::ground_at) are that
    // ground, not the object
    double ground_clearance = 0.3;
};

struct MapChangeScore {
    // Removed objects, moved objects' old places: voxels in the first map / in the later map.
    std::size_t removed_before = 0, removed_kept = 0;
    std::size_t moved_from_before = 0, moved_from_kept = 0;
    // Moved objects' new places and added objects: voxels in the later map, and objects with at
    // least min_voxels of them.
    std::size_t moved_to_voxels = 0, moved_to_present = 0, moved_objects = 0;
    std::size_t added_voxels = 0, added_present = 0, added_objects = 0;
    // First-map voxels outside every box of `unstable` (and of this day's changes): how many,
    // and how many of them the later map keeps.
    std::size_t static_before = 0, static_kept = 0;
    // The first map's static voxels the later map lost (world frame): where the static% goes.
    std::vector<Eigen::Vector3d> static_lost;
};

// Voxel centres in the world frame. `unstable`: every object that changes on any day (so that a
// static voxel is one no day's change touches).
MapChangeScore score_map_changes(const std::vector<Eigen::Vector3d>& first_map,
                                 const std::vector<Eigen::Vector3d>& later_map,
                                 const ObjectChanges& changes,
                                 const std::vector<SiteObject>& unstable,
                                 const MapChangeConfig& config = {});

}  // namespace ltm::eval
