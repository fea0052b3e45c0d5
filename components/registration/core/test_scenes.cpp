#include "registration/core/test_scenes.hpp"

#include <cmath>
#include <random>

#include "registration/core/se3.hpp"

namespace ltm::registration::test {
namespace {
using Eigen::Vector3d;
constexpr double kDeg = M_PI / 180.0;
}  // namespace

void Scene::add_box(const Vector3d& lo, const Vector3d& hi) {
    const Vector3d c = 0.5 * (lo + hi), h = 0.5 * (hi - lo);
    add_quad({c.x(), c.y(), hi.z()}, {h.x(), 0, 0}, {0, h.y(), 0});  // top
    add_quad({lo.x(), c.y(), c.z()}, {0, h.y(), 0}, {0, 0, h.z()});
    add_quad({hi.x(), c.y(), c.z()}, {0, h.y(), 0}, {0, 0, h.z()});
    add_quad({c.x(), lo.y(), c.z()}, {h.x(), 0, 0}, {0, 0, h.z()});
    add_quad({c.x(), hi.y(), c.z()}, {h.x(), 0, 0}, {0, 0, h.z()});
}

double Scene::raycast(const Vector3d& o, const Vector3d& d, double max_range) const {
    double best = max_range;
    bool hit = false;
    for (const Quad& q : quads) {
        const Vector3d n = q.u.cross(q.v);
        const double den = d.dot(n);
        if (std::abs(den) < 1e-12) continue;
        const double t = (q.centre - o).dot(n) / den;
        if (t <= 1e-6 || t >= best) continue;
        const Vector3d r = o + t * d - q.centre;
        if (std::abs(r.dot(q.u)) > q.u.squaredNorm() || std::abs(r.dot(q.v)) > q.v.squaredNorm()) {
            continue;
        }
        best = t;
        hit = true;
    }
    return hit ? best : -1.0;
}

Scene room_scene() {
    Scene s;
    s.add_quad({0, 0, 0}, {20, 0, 0}, {0, 15, 0});   // floor
    s.add_quad({0, 0, 8}, {20, 0, 0}, {0, 15, 0});   // ceiling
    s.add_quad({-20, 0, 4}, {0, 15, 0}, {0, 0, 4});  // walls
    s.add_quad({20, 0, 4}, {0, 15, 0}, {0, 0, 4});
    s.add_quad({0, -15, 4}, {20, 0, 0}, {0, 0, 4});
    s.add_quad({0, 15, 4}, {20, 0, 0}, {0, 0, 4});
    s.add_box({5, 3, 0}, {8, 6, 2});
    s.add_box({-12, -9, 0}, {-9, -4, 3});
    s.add_box({-4, 8, 0}, {-2, 11, 1.5});
    s.add_box({10, -10, 0}, {13, -8, 4});
    s.add_box({-15, 5, 0}, {-14, 6, 6});
    // Slanted panels.
    s.add_quad({0, -12, 2}, Vector3d(3, 0, 0), Vector3d(0, 1.5, 1.5));
    s.add_quad({15, 10, 3}, Vector3d(1.5, 1.5, 0) / std::sqrt(2.0) * 2, Vector3d(0, 0, 2));
    return s;
}

Scene corridor_scene() {
    Scene s;
    s.add_quad({0, 0, 0}, {100, 0, 0}, {0, 2, 0});
    s.add_quad({0, 0, 3}, {100, 0, 0}, {0, 2, 0});
    s.add_quad({0, -2, 1.5}, {100, 0, 0}, {0, 0, 1.5});
    s.add_quad({0, 2, 1.5}, {100, 0, 0}, {0, 0, 1.5});
    return s;
}

Scene street_scene() {
    Scene s;
    s.add_quad({140, 0, 0}, {180, 0, 0}, {0, 40, 0});  // ground
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> setback(8.0, 14.0), length(12.0, 30.0), gap(2.0, 8.0),
        height(6.0, 20.0), depth(8.0, 15.0);
    for (int side : {-1, 1}) {
        for (double x = -30.0; x < 310.0;) {
            const double len = length(rng), sb = setback(rng), dp = depth(rng);
            const double y0 = side * sb, y1 = side * (sb + dp);
            s.add_box({x, std::min(y0, y1), 0}, {x + len, std::max(y0, y1), height(rng)});
            x += len + gap(rng);
        }
        for (double x = -25.0; x < 310.0; x += 17.0) {
            const double y = side * 6.5;
            s.add_box({x, y - 0.15, 0}, {x + 0.3, y + 0.15, 5.0});
        }
        // Parked cars, some gaps between them.
        std::uniform_real_distribution<double> car_gap(1.0, 12.0), car_len(3.8, 5.0);
        for (double x = -28.0 + 5.0 * (side + 1); x < 310.0;) {
            const double len = car_len(rng), y = side * 4.5;
            s.add_box({x, y - 0.9, 0}, {x + len, y + 0.9, 1.5});
            x += len + car_gap(rng);
        }
    }
    return s;
}

common::PointCloud scan_scene(const Scene& scene, const ScanPattern& pattern,
                              const Eigen::Isometry3d& T_world_start,
                              const Eigen::Isometry3d& T_world_end, std::uint32_t seed,
                              bool with_time, bool deskewed_truth) {
    // Only the quads that a ray of this scan can reach (a big speed-up on large scenes).
    Scene near;
    const double travel = (T_world_end.translation() - T_world_start.translation()).norm();
    for (const Quad& q : scene.quads) {
        const double reach = pattern.max_range + q.u.norm() + q.v.norm() + travel;
        if ((q.centre - T_world_start.translation()).norm() < reach) near.quads.push_back(q);
    }
    common::PointCloud cloud;
    std::mt19937 rng(seed);
    std::normal_distribution<double> noise(0.0, pattern.noise);
    const Eigen::Isometry3d motion = T_world_start.inverse() * T_world_end;
    const Eigen::Isometry3d start_inv = T_world_start.inverse();
    for (int j = 0; j < pattern.azimuths; ++j) {
        const double f = double(j) / pattern.azimuths;
        const Eigen::Isometry3d T = T_world_start * scale_motion(motion, f);
        const double az = 2.0 * M_PI * f;
        for (int i = 0; i < pattern.rings; ++i) {
            const double el = (pattern.fov_down + (pattern.fov_up - pattern.fov_down) * i /
                                                      std::max(1, pattern.rings - 1)) *
                              kDeg;
            const Vector3d d(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az),
                             std::sin(el));
            const double range = near.raycast(T.translation(), T.linear() * d, pattern.max_range);
            if (range <= 0.0) continue;
            const Vector3d p = d * (range + noise(rng));
            const Vector3d out = deskewed_truth ? Vector3d(start_inv * (T * p)) : p;
            cloud.points.push_back(out.cast<float>());
            if (with_time) cloud.time.push_back(float(f * pattern.period));
        }
    }
    return cloud;
}

Eigen::Isometry3d make_pose(double x, double y, double z, double roll, double pitch, double yaw) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = (Eigen::AngleAxisd(yaw * kDeg, Vector3d::UnitZ()) *
                  Eigen::AngleAxisd(pitch * kDeg, Vector3d::UnitY()) *
                  Eigen::AngleAxisd(roll * kDeg, Vector3d::UnitX()))
                     .toRotationMatrix();
    T.translation() = Vector3d(x, y, z);
    return T;
}

}  // namespace ltm::registration::test
