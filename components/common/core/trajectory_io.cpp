#include "common/core/trajectory_io.hpp"

#include <cstdio>
#include <fstream>
#include <sstream>

#include "common/core/io_error.hpp"

namespace ltm::common {
namespace {

bool blank(const std::string& line) {
    return line.find_first_not_of(" \t\r") == std::string::npos || line[0] == '#';
}

void write_lines(const std::string& path, const std::string& text) {
    std::ofstream out(path);
    if (!out) throw IoError(path, "cannot open for writing");
    out << text;
    if (!out.flush()) throw IoError(path, "write failed");
}

}  // namespace

std::string format_kitti_pose(const Eigen::Isometry3d& pose) {
    const Eigen::Matrix4d& m = pose.matrix();
    char buf[400];
    std::snprintf(buf, sizeof buf, "%.9e %.9e %.9e %.9e %.9e %.9e %.9e %.9e %.9e %.9e %.9e %.9e\n",
                  m(0, 0), m(0, 1), m(0, 2), m(0, 3), m(1, 0), m(1, 1), m(1, 2), m(1, 3), m(2, 0),
                  m(2, 1), m(2, 2), m(2, 3));
    return buf;
}

std::string format_tum_pose(double stamp, const Eigen::Isometry3d& pose) {
    const Eigen::Quaterniond q(pose.rotation());
    const Eigen::Vector3d t = pose.translation();
    char buf[300];
    std::snprintf(buf, sizeof buf, "%.9f %.9f %.9f %.9f %.9f %.9f %.9f %.9f\n", stamp, t.x(), t.y(),
                  t.z(), q.x(), q.y(), q.z(), q.w());
    return buf;
}

PoseList read_kitti_poses(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw IoError(path, "cannot open");
    PoseList poses;
    std::string line;
    int lineno = 0;
    while (std::getline(in, line)) {
        ++lineno;
        if (blank(line)) continue;
        std::istringstream ss(line);
        Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 4; ++c)
                if (!(ss >> T.matrix()(r, c)))
                    throw IoError(
                        path, "line " + std::to_string(lineno) + ": a KITTI pose needs 12 numbers");
        poses.push_back(T);
    }
    return poses;
}

void write_kitti_poses(const std::string& path, const PoseList& poses) {
    std::string text;
    for (const auto& p : poses) text += format_kitti_pose(p);
    write_lines(path, text);
}

Trajectory read_tum_trajectory(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw IoError(path, "cannot open");
    Trajectory out;
    std::string line;
    int lineno = 0;
    while (std::getline(in, line)) {
        ++lineno;
        if (blank(line)) continue;
        std::istringstream ss(line);
        double v[8];
        for (double& x : v)
            if (!(ss >> x))
                throw IoError(path, "line " + std::to_string(lineno) +
                                        ": a TUM pose needs 8 numbers (t x y z qx qy qz qw)");
        StampedPose sp;
        sp.stamp = v[0];
        sp.pose.linear() =
            Eigen::Quaterniond(v[7], v[4], v[5], v[6]).normalized().toRotationMatrix();
        sp.pose.translation() = Eigen::Vector3d(v[1], v[2], v[3]);
        out.push_back(sp);
    }
    return out;
}

void write_tum_trajectory(const std::string& path, const Trajectory& trajectory) {
    std::string text;
    for (const auto& sp : trajectory) text += format_tum_pose(sp.stamp, sp.pose);
    write_lines(path, text);
}

PoseList camera_to_lidar_poses(const PoseList& camera_poses, const Eigen::Isometry3d& Tr) {
    PoseList out;
    out.reserve(camera_poses.size());
    const Eigen::Isometry3d Tr_inv = Tr.inverse();
    for (const auto& P : camera_poses) out.push_back(Tr_inv * P * Tr);
    return out;
}

}  // namespace ltm::common
