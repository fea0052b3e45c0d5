#include "odometry/core/odometry.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <set>

#include "common/core/kitti_io.hpp"
#include "common/core/trajectory_io.hpp"
#include "odometry/core/scan_cadence.hpp"
#include "registration/core/test_scenes.hpp"

namespace ltm::odometry {
namespace {

using Eigen::Isometry3d;
constexpr double kRadToDeg = 180.0 / M_PI;

// A drive along the synthetic street: 1 m a frame at 10 Hz, gentle weaving.
Isometry3d street_pose(int i) {
    return registration::test::make_pose(1.0 * i, 0.4 * std::sin(i / 5.0), 1.8, 0.0, 0.0,
                                         3.0 * std::sin(i / 8.0));
}

common::PointCloud street_scan(const registration::test::Scene& scene, int i) {
    registration::test::ScanPattern pattern;
    common::PointCloud c =
        registration::test::scan_scene(scene, pattern, street_pose(i), street_pose(i), 100 + i);
    c.stamp = 0.1 * i;
    return c;
}

void expect_near_pose(const Isometry3d& est, const Isometry3d& truth, double t_tol,
                      double r_tol_deg, const std::string& what) {
    const Isometry3d d = truth.inverse() * est;
    EXPECT_LT(d.translation().norm(), t_tol) << what;
    EXPECT_LT(registration::rotation_angle(d) * kRadToDeg, r_tol_deg) << what;
}

class StreetOdometry : public testing::Test {
  protected:
    static void SetUpTestSuite() {
        scene_ = new registration::test::Scene(registration::test::street_scene());
    }
    static void TearDownTestSuite() { delete scene_; }
    static const registration::test::Scene& scene() { return *scene_; }
    static registration::test::Scene* scene_;
};
registration::test::Scene* StreetOdometry::scene_ = nullptr;

TEST_F(StreetOdometry, TracksAndHandsOverLocalMapsWithBoundedMemory) {
    OdometryConfig config;
    config.local_map.half_extent = 40.0;
    config.local_map.switch_distance = 12.0;
    config.keyframe.distance = 2.0;
    Odometry odo(config, street_pose(0));
    std::set<std::uint32_t> finished_ids;
    std::size_t keyframes = 0, new_maps = 0;
    std::vector<std::size_t> memory;
    const int frames = 48;
    for (int i = 0; i < frames; ++i) {
        const FrameResult r = odo.register_frame(street_scan(scene(), i));
        ASSERT_TRUE(r.pose_valid()) << "frame " << i << ": " << r.message;
        EXPECT_EQ(r.status, i == 0 ? FrameStatus::kInitialised : FrameStatus::kTracked);
        expect_near_pose(r.T_odom_lidar, street_pose(i), 0.05, 0.2, "frame " + std::to_string(i));
        EXPECT_TRUE(r.degenerate_directions.empty()) << "frame " << i;
        if (r.keyframe) {
            ++keyframes;
            EXPECT_EQ(r.keyframe->local_map_id, r.local_map_id);
            EXPECT_EQ(r.keyframe->points.size(), r.map_points);
            EXPECT_TRUE(r.keyframe->T_odom_lidar.isApprox(r.T_odom_lidar));
        }
        new_maps += r.new_local_map;
        EXPECT_LE(odo.active_local_maps().size(), std::size_t(config.local_map.max_active_maps));
        EXPECT_EQ(odo.active_local_maps().back().id(), r.local_map_id);
        for (const LocalMap& m : odo.take_finished_local_maps()) {
            EXPECT_TRUE(finished_ids.insert(m.id()).second);  // each handed over once
            EXPECT_LT(m.id(), r.local_map_id);
            EXPECT_GT(m.voxels().usable_voxels(), 100u);
        }
        memory.push_back(odo.memory_bytes());
    }
    // 48 m with a 12 m switch box: maps start at 0, 13, 26 and 39 m.
    EXPECT_EQ(new_maps, 4u);
    EXPECT_EQ(finished_ids.size(), 2u);
    EXPECT_NEAR(double(keyframes), 24.0, 2.0);
    // Bounded by the active maps: the last 16 frames need no more than frames 16-32 did (+25 %).
    const std::size_t early = *std::max_element(memory.begin() + 16, memory.begin() + 32);
    const std::size_t late = *std::max_element(memory.begin() + 32, memory.end());
    EXPECT_LT(double(late), 1.25 * double(early));
    odo.finish_local_maps();
    EXPECT_TRUE(odo.active_local_maps().empty());
    EXPECT_EQ(odo.take_finished_local_maps().size(), 2u);
}

TEST_F(StreetOdometry, NonFinitePointsAreDroppedAndCounted) {
    Odometry odo(OdometryConfig{}, street_pose(0));
    const float nan = std::numeric_limits<float>::quiet_NaN();
    for (int i = 0; i < 4; ++i) {
        common::PointCloud c = street_scan(scene(), i);
        for (int k = 0; k < 10 * i; ++k) {
            c.points[std::size_t(k) * 97] = Eigen::Vector3f(nan, 0.0f, k % 2 ? INFINITY : 1.0f);
        }
        const FrameResult r = odo.register_frame(c);
        ASSERT_TRUE(r.pose_valid()) << r.message;
        EXPECT_EQ(r.dropped_non_finite, std::size_t(10 * i));
        expect_near_pose(r.T_odom_lidar, street_pose(i), 0.05, 0.2, "frame " + std::to_string(i));
    }
}

TEST_F(StreetOdometry, EmptyAndTinyScansAreSkippedWithThePredictionCarriedForward) {
    Odometry odo(OdometryConfig{}, street_pose(0));
    for (int i = 0; i < 3; ++i)
        ASSERT_TRUE(odo.register_frame(street_scan(scene(), i)).pose_valid());
    common::PointCloud empty;
    empty.stamp = 0.3;
    const FrameResult skipped = odo.register_frame(empty);
    EXPECT_EQ(skipped.status, FrameStatus::kSkippedTooFewPoints);
    EXPECT_FALSE(skipped.pose_valid());
    EXPECT_FALSE(skipped.message.empty());
    common::PointCloud tiny = street_scan(scene(), 4);
    tiny.points.resize(20);
    const FrameResult skipped2 = odo.register_frame(tiny);
    EXPECT_EQ(skipped2.status, FrameStatus::kSkippedTooFewPoints);
    // The next real scan is tracked again, in the same segment.
    const FrameResult r = odo.register_frame(street_scan(scene(), 5));
    ASSERT_EQ(r.status, FrameStatus::kRecovered) << r.message;
    EXPECT_EQ(r.segment, 0u);
    EXPECT_NEAR(r.lost_for, 0.3, 1e-9);
    expect_near_pose(r.T_odom_lidar, street_pose(5), 0.05, 0.2, "after the skipped scans");
}

TEST_F(StreetOdometry, SkippedScanCarriesTheConstantVelocityPrediction) {
    Odometry odo(OdometryConfig{}, street_pose(0));
    FrameResult r1, r2;
    ASSERT_TRUE(odo.register_frame(street_scan(scene(), 0)).pose_valid());
    ASSERT_TRUE((r1 = odo.register_frame(street_scan(scene(), 1))).pose_valid());
    ASSERT_TRUE((r2 = odo.register_frame(street_scan(scene(), 2))).pose_valid());
    common::PointCloud empty;
    empty.stamp = 0.3;
    const FrameResult skipped = odo.register_frame(empty);
    const Isometry3d expected = r2.T_odom_lidar * (r1.T_odom_lidar.inverse() * r2.T_odom_lidar);
    EXPECT_TRUE(skipped.T_odom_lidar.isApprox(expected, 1e-9));
    EXPECT_TRUE(odo.pose().isApprox(expected, 1e-9));
}

// A gap in the scans longer than tracking.restart_gap: a new segment, not a fit to the old map
// (the robot may have been carried to a look-alike place); shorter gaps are tracked across.
TEST_F(StreetOdometry, ALongGapBetweenScansStartsANewSegment) {
    Odometry odo(OdometryConfig{}, street_pose(0));
    for (int i = 0; i < 4; ++i)
        ASSERT_TRUE(odo.register_frame(street_scan(scene(), i)).pose_valid());
    common::PointCloud later = street_scan(scene(), 5);
    later.stamp = 0.3 + 1.5;  // 1.5 s gap: within restart_gap (2 s)
    FrameResult r = odo.register_frame(later);
    EXPECT_NE(r.status, FrameStatus::kRestarted) << r.message;
    EXPECT_EQ(r.segment, 0u);
    common::PointCloud carried = street_scan(scene(), 8);
    carried.stamp = later.stamp + 2.5;
    r = odo.register_frame(carried);
    EXPECT_EQ(r.status, FrameStatus::kRestarted);
    EXPECT_EQ(r.segment, 1u);
    EXPECT_NE(r.message.find("gap of 2.5 s"), std::string::npos) << r.message;
    // Off: tracked across.
    OdometryConfig off;
    off.tracking.restart_gap = 0.0;
    Odometry other(off, street_pose(0));
    for (int i = 0; i < 4; ++i)
        ASSERT_TRUE(other.register_frame(street_scan(scene(), i)).pose_valid());
    carried.stamp = 0.3 + 2.5;
    EXPECT_EQ(other.register_frame(carried).segment, 0u);
}

// A keyframe stream pauses while the robot stands (hku-avia: 7.3 s before the second keyframe),
// and every few keyframes are seconds apart: no gap in the stream, no new segment. Before the
// cadence check the second scan restarted (a one-scan segment, the next at the first's pose).
TEST_F(StreetOdometry, AKeyframeStreamsPausesAreNoGap) {
    Odometry odo(OdometryConfig{}, street_pose(0));
    const double stamps[] = {0.0, 7.3, 9.8, 12.6, 14.9, 17.5};  // a stand, then ~2.5 s apart
    for (int i = 0; i < 6; ++i) {
        common::PointCloud c = street_scan(scene(), i);
        c.stamp = stamps[i];
        const FrameResult r = odo.register_frame(c);
        ASSERT_TRUE(r.pose_valid()) << i << ": " << r.message;
        EXPECT_NE(r.status, FrameStatus::kRestarted) << i << ": " << r.message;
        EXPECT_EQ(r.segment, 0u) << i;
    }
    // Then 15 s without a scan (over 5 x its usual 2.6 s): the robot may have been carried.
    common::PointCloud c = street_scan(scene(), 9);
    c.stamp = stamps[5] + 15.0;
    const FrameResult r = odo.register_frame(c);
    EXPECT_EQ(r.status, FrameStatus::kRestarted) << r.message;
    EXPECT_NE(r.message.find("the usual 2.6 s"), std::string::npos) << r.message;
}

TEST(ScanCadence, AGapIsJudgedAgainstTheStreamsUsualInterval) {
    ScanCadence cadence;
    EXPECT_FALSE(cadence.is_break(7.3, 2.0, 5.0));  // nothing known yet: never a break
    EXPECT_TRUE(cadence.is_break(7.3, 2.0, 0.0));   // factor 0: the gap alone
    EXPECT_FALSE(cadence.is_break(7.3, 0.0, 0.0));  // gap 0: off
    for (double dt : {0.1, 0.1, std::nan(""), -1.0, 0.1}) cadence.add(dt);  // bad ones ignored
    EXPECT_TRUE(cadence.known());
    EXPECT_DOUBLE_EQ(cadence.usual(), 0.1);
    EXPECT_TRUE(cadence.is_break(2.2, 2.0, 5.0));   // a 10 Hz stream's 2.2 s pause: a gap
    EXPECT_FALSE(cadence.is_break(1.9, 2.0, 5.0));  // under restart_gap
    for (int i = 0; i < 10; ++i) cadence.add(2.4);  // now keyframes 2.4 s apart (the last 10)
    EXPECT_DOUBLE_EQ(cadence.usual(), 2.4);
    EXPECT_FALSE(cadence.is_break(3.4, 2.0, 5.0));
    EXPECT_TRUE(cadence.is_break(12.1, 2.0, 5.0));
}

TEST_F(StreetOdometry, StampsThatDoNotAdvanceAreRejected) {
    Odometry odo(OdometryConfig{}, street_pose(0));
    ASSERT_TRUE(odo.register_frame(street_scan(scene(), 0)).pose_valid());
    ASSERT_TRUE(odo.register_frame(street_scan(scene(), 1)).pose_valid());
    const Isometry3d before = odo.pose();
    const std::size_t voxels = odo.active_local_maps().back().voxels().size();
    for (const double stamp : {0.05, 0.1, std::numeric_limits<double>::quiet_NaN()}) {
        common::PointCloud c = street_scan(scene(), 2);
        c.stamp = stamp;
        const FrameResult r = odo.register_frame(c);
        EXPECT_EQ(r.status, FrameStatus::kRejectedStamp) << stamp;
        EXPECT_FALSE(r.pose_valid());
        EXPECT_FALSE(r.message.empty());
    }
    EXPECT_TRUE(odo.pose().isApprox(before));
    EXPECT_EQ(odo.active_local_maps().back().voxels().size(), voxels);
    const FrameResult r = odo.register_frame(street_scan(scene(), 2));
    ASSERT_EQ(r.status, FrameStatus::kTracked) << r.message;
    expect_near_pose(r.T_odom_lidar, street_pose(2), 0.05, 0.2, "after the rejected scans");
}

TEST_F(StreetOdometry, DivergenceIsReportedAndNotReturnedAsAPose) {
    Odometry odo(OdometryConfig{}, street_pose(0));
    for (int i = 0; i < 3; ++i)
        ASSERT_TRUE(odo.register_frame(street_scan(scene(), i)).pose_valid());
    const std::size_t voxels = odo.active_local_maps().back().voxels().size();
    // A scan of random clutter: nothing in it matches the street.
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> u(-40.0f, 40.0f);
    common::PointCloud clutter;
    for (int k = 0; k < 20000; ++k)
        clutter.points.emplace_back(u(rng), u(rng), 0.1f * u(rng) + 2.0f);
    clutter.stamp = 0.3;
    const FrameResult bad = odo.register_frame(clutter);
    EXPECT_EQ(bad.status, FrameStatus::kLost) << bad.message;
    EXPECT_FALSE(bad.pose_valid());
    EXPECT_FALSE(bad.keyframe.has_value());
    EXPECT_EQ(odo.active_local_maps().back().voxels().size(), voxels);  // the map is untouched
    EXPECT_TRUE(odo.lost());
    const FrameResult r = odo.register_frame(street_scan(scene(), 4));
    ASSERT_EQ(r.status, FrameStatus::kRecovered) << r.message;
    EXPECT_FALSE(odo.lost());
    expect_near_pose(r.T_odom_lidar, street_pose(4), 0.05, 0.2, "after the divergence");
}

TEST(Odometry, DeskewsScansWithPerPointTimes) {
    // Starting at rest and accelerating into a 135 deg/s turn within 1.5 s, in the room: each
    // revolution smears its scan by up to 13 deg. De-skewing uses the constant-velocity motion,
    // which lags an accelerating turn, so some error remains; without it the error is far larger.
    const registration::test::Scene scene = registration::test::room_scene();
    registration::test::ScanPattern pattern;
    auto pose = [](double t) {
        return registration::test::make_pose(-6.0 + 1.5 * t * t, 1.0, 1.5, 0, 0, 45.0 * t * t);
    };
    double rot_on = 0.0, rot_off = 0.0, trans_on = 0.0;
    for (const bool deskew : {true, false}) {
        OdometryConfig config;
        config.preprocess.deskew = deskew;
        Odometry odo(config, pose(0.0));
        for (int i = 0; i < 15; ++i) {
            const double t = 0.1 * i;
            common::PointCloud c =
                registration::test::scan_scene(scene, pattern, pose(t), pose(t + 0.1), 7 + i, true);
            c.stamp = t;
            const FrameResult r = odo.register_frame(c);
            ASSERT_TRUE(r.pose_valid()) << r.message;
            EXPECT_EQ(r.deskewed, deskew && i >= 1) << i;  // needs a motion estimate
            const Isometry3d d = pose(t).inverse() * r.T_odom_lidar;
            (deskew ? rot_on : rot_off) = registration::rotation_angle(d) * kRadToDeg;
            if (deskew) trans_on = std::max(trans_on, d.translation().norm());
        }
    }
    EXPECT_LT(rot_on, 2.0);
    EXPECT_LT(trans_on, 0.15);
    EXPECT_GT(rot_off, 2.5 * rot_on);
}

TEST_F(StreetOdometry, PlacesScansAtGivenPosesWithoutRegistration) {
    OdometryConfig config;
    config.local_map.half_extent = 40.0;
    config.local_map.switch_distance = 12.0;
    config.keyframe.distance = 2.0;
    Odometry odo(config);
    // Poses 0.3 m and 1 deg off the ones the scans were taken at: registration would move them,
    // placing keeps them.
    const Isometry3d offset = registration::test::make_pose(0.3, -0.2, 0.0, 0.0, 0.0, 1.0);
    std::size_t keyframes = 0, new_maps = 0, finished = 0;
    for (int i = 0; i < 30; ++i) {
        const Isometry3d given = street_pose(i) * offset;
        const FrameResult r = odo.place_frame(street_scan(scene(), i), given);
        ASSERT_TRUE(r.pose_valid()) << "frame " << i << ": " << r.message;
        EXPECT_EQ(r.status, i == 0 ? FrameStatus::kInitialised : FrameStatus::kTracked);
        EXPECT_TRUE(r.T_odom_lidar.isApprox(given, 0.0)) << "frame " << i;
        EXPECT_EQ(r.attempts, 0);  // no registration
        EXPECT_EQ(r.iterations, 0);
        EXPECT_EQ(r.covariance, registration::Matrix6d::Zero());
        if (r.keyframe) {
            ++keyframes;
            EXPECT_TRUE(r.keyframe->T_odom_lidar.isApprox(given, 0.0));
            EXPECT_EQ(r.keyframe->local_map_id, r.local_map_id);
            EXPECT_EQ(r.keyframe->points.size(), r.map_points);
        }
        new_maps += r.new_local_map;
        for (const LocalMap& m : odo.take_finished_local_maps()) {
            EXPECT_GT(m.voxels().usable_voxels(), 100u);
            ++finished;
        }
    }
    EXPECT_EQ(new_maps, 3u);  // as when registered: maps start at 0, 13 and 26 m
    EXPECT_EQ(finished, 1u);
    EXPECT_NEAR(double(keyframes), 15.0, 2.0);
    // A stamp that does not advance and a pose that is not finite leave everything as it was.
    const Isometry3d last = odo.pose();
    common::PointCloud again = street_scan(scene(), 29);
    EXPECT_EQ(odo.place_frame(again, street_pose(30)).status, FrameStatus::kRejectedStamp);
    Isometry3d bad = street_pose(30);
    bad.translation().x() = std::numeric_limits<double>::quiet_NaN();
    const FrameResult r = odo.place_frame(street_scan(scene(), 30), bad);
    EXPECT_EQ(r.status, FrameStatus::kLost);
    EXPECT_FALSE(r.pose_valid());
    EXPECT_NE(r.message.find("not finite"), std::string::npos) << r.message;
    EXPECT_TRUE(odo.pose().isApprox(last, 0.0));
}

// The median distance from each point of `a` (every 10th) to its nearest in `b` [m].
double median_nearest(const std::vector<Eigen::Vector3f>& a,
                      const std::vector<Eigen::Vector3f>& b) {
    std::vector<float> d;
    for (std::size_t i = 0; i < a.size(); i += 10) {
        float best = std::numeric_limits<float>::max();
        for (const Eigen::Vector3f& q : b) best = std::min(best, (a[i] - q).squaredNorm());
        d.push_back(std::sqrt(best));
    }
    std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
    return d[d.size() / 2];
}

TEST(Odometry, PlacedScansAreDeskewedByTheMotionBetweenTheGivenPoses) {
    // A steady 90 deg/s turn while driving at 5 m/s in the room (a constant twist in the sensor
    // frame): each sweep smears by 9 deg. The motion between the given poses is the true one, so
    // de-skewing is exact.
    const registration::test::Scene scene = registration::test::room_scene();
    registration::test::ScanPattern pattern;
    pattern.noise = 0.0;
    registration::Vector6d twist;
    twist << 5.0, 0.0, 0.0, 0.0, 0.0, M_PI / 2;
    auto pose = [&](double t) {
        return registration::test::make_pose(-6.0, 1.0, 1.5, 0, 0, 0) *
               registration::se3_exp(t * twist);
    };
    double error[2] = {0.0, 0.0};
    for (const bool deskew : {true, false}) {
        OdometryConfig config;
        config.preprocess.deskew = deskew;
        config.keyframe.distance = 0.1;  // every scan a keyframe
        Odometry odo(config);
        FrameResult r;
        for (int i = 0; i < 3; ++i) {
            const double t = 0.1 * i;
            common::PointCloud c =
                registration::test::scan_scene(scene, pattern, pose(t), pose(t + 0.1), 7 + i, true);
            c.stamp = t;
            r = odo.place_frame(c, pose(t));
            ASSERT_TRUE(r.pose_valid()) << r.message;
            EXPECT_EQ(r.deskewed, deskew && i >= 1) << i;  // needs the motion from a given pose
        }
        ASSERT_TRUE(r.keyframe.has_value());
        // What ideal de-skewing yields: the same scan in the sensor frame at its start.
        const common::PointCloud truth =
            registration::test::scan_scene(scene, pattern, pose(0.2), pose(0.3), 9, true, true);
        error[deskew ? 0 : 1] = median_nearest(r.keyframe->points, truth.points);
    }
    EXPECT_LT(error[0], 0.005);
    EXPECT_GT(error[1], 0.05);
}

TEST(Odometry, InvalidConfigurationThrowsNamingTheKey) {
    OdometryConfig config;
    config.voxel_size = -1.0;
    try {
        Odometry odo(config);
        FAIL() << "no exception";
    } catch (const common::ConfigError& e) {
        EXPECT_EQ(std::string(e.what()), "odometry.voxel_size: must be > 0 (got -1)");
        EXPECT_EQ(e.key(), "odometry.voxel_size");
    }
}

TEST(Odometry, RealKittiFixtureMatchesTheReferenceMotion) {
    const std::string dir = LTM_SOURCE_DIR "/tests/fixtures/kitti00_mini";
    const auto scans = common::list_kitti_scans(dir);
    ASSERT_EQ(scans.size(), 3u);
    const auto times = common::read_times(dir + "/times.txt");
    const auto reference =
        common::camera_to_lidar_poses(common::read_kitti_poses(dir + "/poses_semantickitti.txt"),
                                      common::read_kitti_calib_tr(dir + "/calib.txt"));
    Odometry odo(preset_config(SensorPreset::kHdl64));
    std::vector<Isometry3d> est;
    for (std::size_t i = 0; i < scans.size(); ++i) {
        common::PointCloud c = common::read_kitti_bin(scans[i]);
        c.stamp = times[i];
        const FrameResult r = odo.register_frame(c);
        ASSERT_TRUE(r.pose_valid()) << r.message;
        est.push_back(r.T_odom_lidar);
    }
    for (std::size_t i = 1; i < est.size(); ++i) {
        expect_near_pose(est[i - 1].inverse() * est[i], reference[i - 1].inverse() * reference[i],
                         0.05, 0.2, "frame " + std::to_string(i));
    }
}

}  // namespace
}  // namespace ltm::odometry
