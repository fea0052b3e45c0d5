#pragma once
// The simulator's static objects of a session (ltm_sim's objects.txt) and what changed between
// the first session and a later one: removed, moved (old and new place) and added objects, as
// oriented boxes on the ground.
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

namespace ltm::eval {

struct SiteObject {
    std::uint32_t id = 0;
    std::string kind;
    double x = 0.0, y = 0.0, base_z = 0.0;  // [m] world frame: centre of the footprint, ground
    double yaw_deg = 0.0;
    double length = 0.0, width = 0.0, height = 0.0;  // [m] along its heading, across, up
    bool changed = false;  // the simulator marks it changed in some session
    // [m] the terrain's height along its long axis, evenly spaced from one end to the other
    // (objects.txt's optional last columns); empty: base_z all along.
    std::vector<double> ground_z;

    // True when p lies in the box grown by `margin` on every side.
    bool contains(const Eigen::Vector3d& p, double margin) const;
    // The ground under p: ground_z interpolated at p's place along the long axis (clamped to
    // its ends), base_z without it. A fence on a slope is sunk to its lowest ground (base_z) and
    // stands on ground up to half a metre higher at its other end.
    double ground_at(const Eigen::Vector3d& p) const;
};

// objects.txt: `id kind x y base_z yaw_deg length width height changed [ground_z ...]` a line
// (ground_z: none, or at least two heights), `#` comments.
// Throws common::IoError naming the file and line on bad input.
std::vector<SiteObject> read_site_objects(const std::string& path);

struct ObjectChanges {
    std::vector<SiteObject> removed;     // in the first session only (its place there)
    std::vector<SiteObject> moved_from;  // same id in both, moved: its first place ...
    std::vector<SiteObject> moved_to;    // ... and its place in the later session (same order)
    std::vector<SiteObject> added;       // in the later session only
};

// Objects whose footprint centre moved more than `move_tolerance` [m] or turned are moved.
ObjectChanges diff_objects(const std::vector<SiteObject>& first,
                           const std::vector<SiteObject>& later, double move_tolerance = 0.1);

}  // namespace ltm::eval
