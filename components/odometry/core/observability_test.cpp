// Observability of the odometry's fits (issue 27): the criterion on the fit's normal equations,
// large steps along a weakly constrained road, and a corridor where the position along the
// corridor is not observable (never reported as tracked).
#include "odometry/core/observability.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "odometry/core/odometry.hpp"
#include "odometry/core/step_search.hpp"
#include "registration/core/test_scenes.hpp"

namespace ltm::odometry {
namespace {

using registration::Matrix6d;
using registration::Vector6d;
using registration::test::make_pose;

// sum J^T J of point-to-plane residuals at points p with normals n.
Matrix6d hessian_of(const std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>>& pn) {
    Matrix6d H = Matrix6d::Zero();
    for (const auto& [p, n] : pn) {
        Vector6d J;
        J << n, p.cross(n);
        H += J * J.transpose();
    }
    return H;
}

TEST(Observability, CorridorIsWeakAlongItsAxisRoomIsNot) {
    std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> corridor, room;
    for (int i = -20; i <= 20; ++i) {
        for (int k = 0; k < 3; ++k) {
            corridor.push_back({{double(i), 2.0, double(k)}, {0, -1, 0}});
            corridor.push_back({{double(i), -2.0, double(k)}, {0, 1, 0}});
            corridor.push_back({{double(i), double(k) - 1.0, -1.0}, {0, 0, 1}});
            room.push_back({{double(i), 2.0, double(k)}, {0, -1, 0}});
            room.push_back({{double(i), double(k) - 1.0, -1.0}, {0, 0, 1}});
            room.push_back({{10.0, double(i) / 5.0, double(k)}, {-1, 0, 0}});
        }
    }
    const Observability c = translation_observability(hessian_of(corridor), 0.04);
    EXPECT_EQ(c.constrained, 2);
    EXPECT_LT(c.information[0], 1e-6);
    EXPECT_GT(std::abs(c.weakest().x()), 0.99);
    // Normalised by the total weight; the rotation takes its share.
    EXPECT_LE(c.information.sum(), 1.0 + 1e-9);
    EXPECT_GT(c.information.sum(), 0.5);
    const Observability r = translation_observability(hessian_of(room), 0.04);
    EXPECT_EQ(r.constrained, 3);
    EXPECT_FALSE(r.weak());
    // Nothing: no direction constrained, no crash.
    EXPECT_EQ(translation_observability(Matrix6d::Zero(), 0.04).constrained, 0);
}

TEST(Observability, HonestCovarianceScalesAndFloors) {
    ObservabilityConfig c;
    c.covariance_scale = 4.0;
    c.covariance_floor = 0.02;
    const Matrix6d fit = Matrix6d::Identity() * 1e-6;
    const Matrix6d h = honest_covariance(fit, c);
    EXPECT_NEAR(h(0, 0), 4e-6 + 4e-4, 1e-12);
    EXPECT_NEAR(h(5, 5), 4e-6, 1e-12);  // rotation: scaled only
}

TEST(Observability, CovarianceWidenedAlongEveryWeakDirectionButAFoundOne) {
    std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> corridor;
    for (int i = -20; i <= 20; ++i) {
        for (int k = 0; k < 3; ++k) {
            corridor.push_back({{double(i), 2.0, double(k)}, {0, -1, 0}});
            corridor.push_back({{double(i), -2.0, double(k)}, {0, 1, 0}});
            corridor.push_back({{double(i), double(k) - 1.0, -1.0}, {0, 0, 1}});
        }
    }
    const Observability o = translation_observability(hessian_of(corridor), 0.04);
    ASSERT_EQ(o.constrained, 2);
    const Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
    Matrix6d c = Matrix6d::Identity() * 1e-4;
    inflate_weak(o, R, Eigen::Vector3d::Zero(), 0.5, &c);
    EXPECT_NEAR(c(0, 0), 1e-4 + 0.25, 1e-6);  // along the corridor: the step's share
    EXPECT_NEAR(c(1, 1), 1e-4, 1e-9);         // across it and up: the fit's own
    EXPECT_NEAR(c(2, 2), 1e-4, 1e-9);
    EXPECT_NEAR(c(3, 3), 1e-4, 1e-9);  // rotation untouched
    // In map axes turned 90 deg about z, the weak direction is the odometry's y.
    Matrix6d turned = Matrix6d::Identity() * 1e-4;
    inflate_weak(o, Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix(),
                 Eigen::Vector3d::Zero(), 0.5, &turned);
    EXPECT_NEAR(turned(1, 1), 1e-4 + 0.25, 1e-6);
    EXPECT_NEAR(turned(0, 0), 1e-4, 1e-9);
    // A position the search along it found is not widened.
    Matrix6d found = Matrix6d::Identity() * 1e-4;
    inflate_weak(o, R, Eigen::Vector3d::UnitX(), 0.5, &found);
    EXPECT_NEAR(found(0, 0), 1e-4, 1e-9);
}

// A straight tree-lined road: the ground, and a trunk about every 5 m (irregular) on alternating
// sides: along the road only the trunks fix the position.
registration::test::Scene pole_road() {
    registration::test::Scene s;
    s.add_quad({200, 0, -1.8}, {260, 0, 0}, {0, 40, 0});
    for (int i = 0; i < 90; ++i) {
        const double x = -30.0 + 5.0 * i + 1.5 * std::sin(1.7 * i);
        const double y = (i % 2) ? 6.0 + (i % 3) : -7.0 - (i % 4);
        const double h = 0.4 + 0.1 * (i % 3);
        s.add_box({x - h, y - h, -1.8}, {x + h, y + h, 3.0});
    }
    return s;
}

registration::test::ScanPattern pattern() {
    registration::test::ScanPattern p;
    p.rings = 32;
    p.azimuths = 900;
    p.max_range = 60.0;
    return p;
}

// Steps of 7 m a scan (14 m/s, every 5th scan of a 10 Hz sensor), from a standing start.
std::vector<FrameResult> drive(const registration::test::Scene& scene, const OdometryConfig& c,
                               int frames, double step, std::vector<double>* truth_x) {
    Odometry odo(c);
    std::vector<FrameResult> out;
    for (int i = 0; i < frames; ++i) {
        const Eigen::Isometry3d T = make_pose(step * i, 0.0, 0.0, 0, 0, 0);
        common::PointCloud cloud = registration::test::scan_scene(scene, pattern(), T, T, 7 + i);
        cloud.stamp = 0.5 * i;
        out.push_back(odo.register_frame(cloud));
        out.back().keyframe.reset();
        truth_x->push_back(step * i);
    }
    return out;
}

TEST(Observability, LargeStepsAlongAWeakRoadAreNeverRegisteredWhenOff) {
    OdometryConfig c;
    std::vector<double> truth;
    const std::vector<FrameResult> r = drive(pole_road(), c, 12, 7.0, &truth);
    int weak = 0;
    for (std::size_t i = 1; i < r.size(); ++i) {
        ASSERT_TRUE(r[i].pose_valid()) << i << ": " << r[i].message;
        const double err = std::abs(r[i].T_odom_lidar.translation().x() - truth[i]);
        weak += r[i].constrained_directions < 3;
        // Never reported as registered while more than 1 m off.
        if (r[i].registered()) {
            EXPECT_LT(err, 1.0) << "scan " << i << " " << r[i].search_used;
        }
    }
    EXPECT_GT(weak, 0);  // the road is weak along x: the check ran
    // (Whether the search finds these steps depends on how distinct the trunks are: this regular
    // row from a one-scan map mostly is not, and the scans are then degenerate. The simulated
    // roads of `./ltm bench hard_cases --observe` measure how often it finds them.)
}

TEST(Observability, APlainCorridorIsNeverTracked) {
    OdometryConfig c;
    std::vector<double> truth;
    const std::vector<FrameResult> r =
        drive(registration::test::corridor_scene(), c, 6, 1.0, &truth);
    for (std::size_t i = 1; i < r.size(); ++i) {
        ASSERT_TRUE(r[i].pose_valid()) << i << ": " << r[i].message;
        // Degenerate, or (scans 0.5 s apart, the position along the axis held at the prediction
        // while the fit had slid toward the truth) a new segment at the prediction: either way the
        // position along the corridor is published as a guess, never as tracked.
        EXPECT_TRUE(r[i].status == FrameStatus::kDegenerate ||
                    r[i].status == FrameStatus::kRestarted)
            << i << ": " << r[i].search_used << " " << r[i].message;
        EXPECT_FALSE(r[i].registered());
        if (r[i].status == FrameStatus::kDegenerate) {
            EXPECT_TRUE(r[i].degenerate());
        }
        // The covariance along the corridor says the position there is a guess.
        EXPECT_GE(r[i].covariance(0, 0),
                  c.observability.degenerate_min_sigma * c.observability.degenerate_min_sigma);
    }
}

// At 10 Hz the steps down a corridor are small and the fit agrees with the prediction: the
// registration cannot observe the axis (solution remapping leaves it at the prediction), so the
// scan is degenerate, never "tracked", and the walk goes on at the speed it had.
TEST(Observability, SmallStepsDownAPlainCorridorAreDegenerateNotTracked) {
    OdometryConfig c;
    Odometry odo(c);
    const auto scene = registration::test::corridor_scene();
    int degenerate = 0;
    for (int i = 0; i < 4; ++i) {  // (the synthetic corridor's 5th scan is refused either way)
        const Eigen::Isometry3d T = make_pose(0.12 * i, 0.0, 0.0, 0, 0, 0);
        common::PointCloud cloud = registration::test::scan_scene(scene, pattern(), T, T, 3 + i);
        cloud.stamp = 0.1 * i;
        const FrameResult r = odo.register_frame(cloud);
        ASSERT_TRUE(r.pose_valid()) << i << ": " << r.message;
        bool unobserved_translation = false;
        for (const registration::Vector6d& v : r.degenerate_directions)
            unobserved_translation |= v.head<3>().norm() > 0.7;
        EXPECT_FALSE(r.registered() && unobserved_translation)
            << "scan " << i << " reported " << to_string(r.status) << " with the axis unobserved";
        degenerate += r.status == FrameStatus::kDegenerate;
    }
    EXPECT_GT(degenerate, 0);
}

TEST(StepSearch, FindsThePolesAlongTheRoad) {
    // A map of the road from the origin; the scan from 9 m further: the support along x peaks
    // at 9 m, not at 0 where the ground fits as well.
    OdometryConfig c;
    Odometry odo(c);
    const auto scene = pole_road();
    common::PointCloud first = registration::test::scan_scene(
        scene, pattern(), Eigen::Isometry3d::Identity(), Eigen::Isometry3d::Identity(), 1);
    first.stamp = 0.0;
    ASSERT_EQ(odo.register_frame(first).status, FrameStatus::kInitialised);
    const Eigen::Isometry3d T = make_pose(9.0, 0, 0, 0, 0, 0);
    const common::PointCloud second = registration::test::scan_scene(scene, pattern(), T, T, 2);
    std::vector<Eigen::Vector3f> pts;
    for (std::size_t i = 0; i < second.points.size(); i += 8) pts.push_back(second.points[i]);
    const LocalMap& map = odo.active_local_maps().back();
    registration::ImlsParams imls;
    imls.bandwidth = float(c.voxel_size);
    ProfileRequest q;
    q.from = -2.0;
    q.to = 14.0;
    q.spacing = c.voxel_size;
    const Profile p = search_along(pts, map.voxels(), imls, map.T_odom_map().inverse(),
                                   Eigen::Vector3d::UnitX(), q);
    EXPECT_NEAR(p.best_offset, 9.0, 1.0);  // the fit from there does the rest
    EXPECT_GT(p.contrast(), 1.3);
}

}  // namespace
}  // namespace ltm::odometry
