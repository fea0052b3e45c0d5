#pragma once
// Metres of new ground on a day: the length of the day's true path farther than a radius (in the
// ground plane) from every earlier day's true path.
#include <Eigen/Core>
#include <vector>

namespace ltm::eval {

struct NewGroundConfig {
    double radius = 10.0;   // [m] a path point this close to an earlier path is not new
    double max_step = 5.0;  // [m] consecutive poses farther apart are a jump (a kidnap), not road
};

// `path`: the day's true positions in order; `earlier`: every earlier day's. A step counts when
// both its ends are new. Only x and y are compared.
double new_ground_length(const std::vector<Eigen::Vector3d>& path,
                         const std::vector<Eigen::Vector3d>& earlier,
                         const NewGroundConfig& config = {});

}  // namespace ltm::eval
