#pragma once
// Metres of new ground on a day: the length of the day's true path farther than a radius (in the
// ground plane) from every earlier day's true path; and how much of it a map covers (a map voxel
// near the path), i.e. was mapped.
#include <Eigen/Core>
#include <vector>

namespace ltm::eval {

struct NewGroundConfig {
    double radius = 10.0;     // [m] a path point this close to an earlier path is not new
    double max_step = 5.0;    // [m] consecutive poses farther apart are a jump (a kidnap), not road
    double map_radius = 1.5;  // [m] a path point with a map voxel this near (3D) is mapped
};

struct NewGround {
    double driven = 0.0;  // [m] new ground on the path
    double mapped = 0.0;  // [m] of it, with map voxels near both ends of each step
};

// `path`: the day's true positions in order; `earlier`: every earlier day's; `map`: voxel centres
// in the same frame (empty: nothing mapped). A step counts when both its ends are new (only x and
// y compared).
NewGround new_ground(const std::vector<Eigen::Vector3d>& path,
                     const std::vector<Eigen::Vector3d>& earlier,
                     const std::vector<Eigen::Vector3d>& map, const NewGroundConfig& config = {});

}  // namespace ltm::eval
