#pragma once
// The figure of one day of a lifelong run (SVG top view): the true path, earlier days' paths,
// the published map poses coloured by their error, and what changed on the site (removed
// objects, moved objects' old and new places, added objects) as outlines.
#include <string>
#include <vector>

#include "common/core/trajectory_io.hpp"
#include "evaluation/core/site_objects.hpp"

namespace ltm::eval {

struct LifelongDayFigure {
    std::string title = "Lifelong day (top view)";
    std::vector<Eigen::Vector3d> earlier_paths;  // every earlier day's true positions
    common::PoseList truth;                      // the day's true poses, one per scan
    common::PoseList aligned;                    // published poses in the world, one per scan
    std::vector<double> error;                   // [m] per scan, negative: no pose
    double good = 0.1, wrong = 0.5;              // [m] colour bands: <= good, <= wrong, above
    ObjectChanges changes;
};

std::string lifelong_day_svg(const LifelongDayFigure& figure);

}  // namespace ltm::eval
