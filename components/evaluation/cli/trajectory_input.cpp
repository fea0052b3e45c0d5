#include "evaluation/cli/trajectory_input.hpp"

#include "common/cli/cli.hpp"
#include "common/core/kitti_io.hpp"
#include "evaluation/core/frames.hpp"

namespace ltm::eval::cli {

LoadedTrajectory load_trajectory(const std::string& path, const std::string& format) {
    LoadedTrajectory out;
    if (format == "tum") {
        out.poses = common::read_tum_trajectory(path);
        out.stamped = true;
        return out;
    }
    const common::PoseList poses = common::read_kitti_poses(path);
    for (std::size_t i = 0; i < poses.size(); ++i)
        out.poses.push_back({static_cast<double>(i), poses[i]});
    return out;
}

common::PoseList convert_frame(const common::PoseList& poses, const std::string& from,
                               const std::string& to, const std::string& calib) {
    if (from == to) return poses;
    if (calib.empty())
        throw common::cli::UsageError("converting poses from the " + from + " to the " + to +
                                      " frame needs --calib calib.txt");
    const Eigen::Isometry3d Tr = common::read_kitti_calib_tr(calib);
    return from == "camera" ? camera_to_lidar(poses, Tr) : lidar_to_camera(poses, Tr);
}

}  // namespace ltm::eval::cli
