#pragma once
// The evaluation's standard pictures, as SVG text: a trajectory top view and errors along the
// distance travelled.
#include <string>
#include <vector>

#include "common/core/trajectory_io.hpp"
#include "evaluation/core/place_recognition.hpp"

namespace ltm::eval {

// The plane a top view shows: LiDAR/world frames are z-up (x-y), KITTI camera frames y-down
// (x-z); kAuto drops the axis along which the reference extends least.
enum class TopViewPlane { kAuto, kXY, kXZ, kYZ };

struct TrajectoryFigure {
    std::string title = "Trajectory (top view)";
    common::PoseList reference;      // ground truth
    common::PoseList estimate;       // already aligned to the reference
    std::vector<LoopPair> loops;     // drawn as segments between estimate poses
    std::vector<bool> loop_correct;  // empty, or per loop: green when true, red when false
    TopViewPlane plane = TopViewPlane::kAuto;
};
std::string trajectory_svg(const TrajectoryFigure& figure);

struct ErrorFigure {
    std::string title = "Error along the trajectory";
    std::vector<double> distance;           // [m] along the reference, one per pose
    std::vector<double> position_error;     // [m] aligned position error, one per pose
    std::vector<double> step_translation;   // [m] RPE of frames (i, i+1), plotted at distance[i+1]
    std::vector<double> step_rotation_deg;  // [deg] same pairs
};
std::string errors_svg(const ErrorFigure& figure);

// The two axes (0 x, 1 y, 2 z) a plane shows; kAuto resolved with the poses.
void plane_axes(TopViewPlane plane, const common::PoseList& poses, int& a, int& b);

}  // namespace ltm::eval
