// The odometry with a motion prior from the robot (issue 27, item 5): a gyro through a sudden
// spin, and wheel odometry along a corridor whose walls cannot say how far the sensor went.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "odometry/core/motion_prior.hpp"
#include "odometry/core/odometry.hpp"
#include "registration/core/test_scenes.hpp"

namespace ltm::odometry {
namespace {

using Eigen::Isometry3d;
using Eigen::Vector3d;
constexpr double kRadToDeg = 180.0 / M_PI;
constexpr double kPeriod = 0.1;  // [s] scans at 10 Hz, each sweep as long

registration::test::ScanPattern small_pattern() {
    registration::test::ScanPattern p;
    p.rings = 16;
    p.azimuths = 360;
    p.period = kPeriod;
    return p;
}

// Scans along `truth` (T_world_lidar at time t): sweeps distorted by the motion, with per-point
// times; a prior (when given) gets gyro samples at 200 Hz with a bias and wheel poses at 50 Hz up
// to each sweep's end. Returns the worst position error [m] and heading error [deg] against the
// truth (relative to the first pose), and fills the frames' results.
template <typename Truth>
void run(const registration::test::Scene& scene, Truth truth, int scans, MotionPrior* prior,
         bool wheels, std::vector<FrameResult>* results, double* worst_m, double* worst_deg) {
    Odometry odo(OdometryConfig{}, truth(0.0));
    odo.set_prior(prior);
    int imu = 0, wheel = 0;
    *worst_m = *worst_deg = 0.0;
    for (int i = 0; i < scans; ++i) {
        const double t = kPeriod * i;
        if (prior != nullptr) {
            for (; imu / 200.0 <= t + kPeriod; ++imu) {
                const double s = imu / 200.0, h = 1e-4;
                const Eigen::Matrix3d dR = truth(s).linear().transpose() * truth(s + h).linear();
                const Eigen::AngleAxisd aa(dR);
                prior->add_imu(s, aa.axis() * aa.angle() / h + Vector3d(0.002, -0.001, 0.003));
            }
            for (; wheels && wheel / 50.0 <= t + kPeriod; ++wheel)
                prior->add_wheel(wheel / 50.0, truth(0.0).inverse() * truth(wheel / 50.0));
        }
        common::PointCloud c = registration::test::scan_scene(scene, small_pattern(), truth(t),
                                                              truth(t + kPeriod), 100 + i, true);
        c.stamp = t;
        results->push_back(odo.register_frame(c));
        const Isometry3d d = truth(t).inverse() * results->back().T_odom_lidar;
        *worst_m = std::max(*worst_m, d.translation().norm());
        *worst_deg = std::max(*worst_deg, registration::rotation_angle(d) * kRadToDeg);
    }
}

// Standing in the room, then a sudden spin at 180 deg/s (18 deg a scan) for 2 s: the gyro turns
// every prediction with the sensor, so no scan needs the search, and the poses stay on the truth.
TEST(PriorSpin, GyroCarriesTheOdometryThroughASpin) {
    const registration::test::Scene scene = registration::test::room_scene();
    const auto truth = [](double t) {
        const double yaw = t < 0.5 ? 0.0 : M_PI * std::min(t - 0.5, 2.0);
        Isometry3d T = registration::test::make_pose(-4.0, 2.0, 1.5, 0, 0, 0);
        T.linear() = Eigen::AngleAxisd(yaw, Vector3d::UnitZ()).matrix();
        return T;
    };
    MotionPrior prior;
    std::vector<FrameResult> with;
    double worst_m = 0.0, worst_deg = 0.0;
    run(scene, truth, 28, &prior, false, &with, &worst_m, &worst_deg);
    int searched = 0;
    for (std::size_t i = 0; i < with.size(); ++i) {
        EXPECT_TRUE(with[i].pose_valid()) << i << ": " << with[i].message;
        searched += with[i].searched;
    }
    EXPECT_EQ(searched, 0);
    EXPECT_LT(worst_m, 0.05);
    EXPECT_LT(worst_deg, 0.5);
    // Without the gyro the spin's start is a surprise the odometry has to search for.
    std::vector<FrameResult> without;
    double m0 = 0.0, d0 = 0.0;
    run(scene, truth, 8, nullptr, false, &without, &m0, &d0);
    int searched_without = 0;
    for (const FrameResult& r : without) searched_without += r.searched;
    EXPECT_GT(searched_without, 0);
}

// Along a corridor of plain walls at 3 m/s the fit cannot see how far the sensor went; the
// wheel odometry fills that direction (and only that one).
TEST(PriorSpin, WheelsFillTheDirectionTheCorridorCannotSee) {
    const registration::test::Scene scene = registration::test::corridor_scene();
    const auto truth = [](double t) {
        const double v = t < 0.3 ? 1.0 * t : 0.3 + 3.0 * (t - 0.3);  // speeds up at 0.3 s
        return registration::test::make_pose(-60.0 + v, 0.0, 1.5, 0, 0, 0);
    };
    MotionPriorConfig c;
    MotionPrior prior(c);
    std::vector<FrameResult> with, without;
    double with_m = 0.0, with_deg = 0.0, without_m = 0.0, without_deg = 0.0;
    run(scene, truth, 20, &prior, true, &with, &with_m, &with_deg);
    run(scene, truth, 20, nullptr, false, &without, &without_m, &without_deg);
    int degenerate = 0;
    for (const FrameResult& r : with) degenerate += r.degenerate();
    EXPECT_GT(degenerate, 10);  // the corridor is degenerate for the fit
    EXPECT_LT(with_m, 0.1);
    EXPECT_GT(without_m, 0.5);  // without the wheels the odometry lags behind
}

}  // namespace
}  // namespace ltm::odometry
