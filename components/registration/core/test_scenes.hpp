#pragma once
// Synthetic scenes for the odometry tests: rectangles in space, ray-cast by a spinning LiDAR with
// fixed-seed noise. Test-only code (linked into the test executable, not the library).
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "common/core/point_cloud.hpp"

namespace ltm::registration::test {

// A rectangle: centre + u * [-1, 1] + v * [-1, 1] (u, v orthogonal half-edges).
struct Quad {
    Eigen::Vector3d centre, u, v;
};

struct Scene {
    std::vector<Quad> quads;
    void add_quad(const Eigen::Vector3d& centre, const Eigen::Vector3d& u,
                  const Eigen::Vector3d& v) {
        quads.push_back({centre, u, v});
    }
    // The five visible faces of an axis-aligned box standing on z = z0 (no bottom).
    void add_box(const Eigen::Vector3d& min, const Eigen::Vector3d& max);
    // Distance along the ray to the first hit (or a negative value).
    double raycast(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir,
                   double max_range) const;
};

// A closed room 40 x 30 x 8 m with boxes and slanted panels: every direction is constrained.
Scene room_scene();
// A corridor 200 m along x, 4 m wide, 3 m high, plain walls: translation along x unconstrained.
Scene corridor_scene();
// A street 300 m along x with buildings of varied setbacks, poles and a ground plane.
Scene street_scene();

struct ScanPattern {
    int rings = 32;
    int azimuths = 720;
    double fov_up = 15.0;     // [deg]
    double fov_down = -25.0;  // [deg]
    double max_range = 60.0;  // [m]
    double noise = 0.01;      // range noise sigma [m]
    double period = 0.1;      // [s] one revolution; per-point times span it
};

// One scan taken while the sensor moves from T_world_start to T_world_end over the revolution
// (pass the same pose twice for a still sensor). Points are in the sensor frame at the START of
// the scan when `deskewed_truth` is true (what ideal de-skewing yields), otherwise in the sensor
// frame at their own capture time (what a real spinning LiDAR reports). Times are filled when
// `with_time`.
common::PointCloud scan_scene(const Scene& scene, const ScanPattern& pattern,
                              const Eigen::Isometry3d& T_world_start,
                              const Eigen::Isometry3d& T_world_end, std::uint32_t seed,
                              bool with_time = false, bool deskewed_truth = false);

// A rigid transform from a translation [m] and Euler angles roll, pitch, yaw [deg].
Eigen::Isometry3d make_pose(double x, double y, double z, double roll_deg, double pitch_deg,
                            double yaw_deg);

}  // namespace ltm::registration::test
