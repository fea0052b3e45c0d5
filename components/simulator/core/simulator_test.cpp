#include "simulator/core/simulator.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "common/core/point_labels.hpp"
#include "simulator/core/scenario_yaml.hpp"

namespace ltm::sim {
namespace {

// A small yard, a 20 m straight route, a pedestrian crossing ahead of the robot.
ScenarioConfig small_world(std::uint64_t seed) {
    ScenarioConfig sc;
    sc.name = "small";
    sc.seed = seed;
    make_sensor_preset("vlp16", sc.sensor);
    sc.world.margin = 25;
    sc.world.terrain.amplitude = 0.5;
    sc.world.terrain.wavelength = 60;
    sc.world.substation.yard = Eigen::AlignedBox2d(Eigen::Vector2d(0, 0), Eigen::Vector2d(30, 20));
    sc.world.substation.bay_width = 10;
    SessionConfig s;
    s.route.waypoints = {{2, 10, 0}, {28, 10, 0}};
    s.route.speed = 4.0;
    ActorConfig walker;
    walker.kind = ActorKind::kPedestrian;
    walker.waypoints = {{14, 4}, {14, 16}};
    walker.speed = 1.5;
    s.actors.placed.push_back(walker);
    sc.sessions.push_back(s);
    return sc;
}

double point_triangle_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                               const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    // Closest point on a triangle (Ericson, Real-Time Collision Detection 5.1.5).
    const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
    const double d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0 && d2 <= 0) return (p - a).norm();
    const Eigen::Vector3d bp = p - b;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0 && d4 <= d3) return (p - b).norm();
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) return (p - (a + d1 / (d1 - d3) * ab)).norm();
    const Eigen::Vector3d cp = p - c;
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0 && d5 <= d6) return (p - c).norm();
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) return (p - (a + d2 / (d2 - d6) * ac)).norm();
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
        return (p - (b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b))).norm();
    }
    const double denom = 1.0 / (va + vb + vc);
    return (p - (a + ab * (vb * denom) + ac * (vc * denom))).norm();
}

double distance_to_mesh(const common::PlyMesh& mesh, const Eigen::Vector3d& p) {
    double best = 1e9;
    for (const auto& t : mesh.triangles) {
        const Eigen::Vector3d a = mesh.vertices[t[0]].cast<double>();
        if ((a - p).squaredNorm() > 400.0) continue;  // triangles here are under 20 m across
        best = std::min(best, point_triangle_distance(p, a, mesh.vertices[t[1]].cast<double>(),
                                                      mesh.vertices[t[2]].cast<double>()));
    }
    return best;
}

TEST(Simulator, DeterministicBySeedInAnyOrder) {
    const Simulator a(small_world(11)), b(small_world(11)), c(small_world(12));
    ASSERT_GT(a.num_scans(), 20u);
    SimScan a3, a5, b3, c3;
    ASSERT_TRUE(a.scan(5, a5));
    ASSERT_TRUE(a.scan(3, a3));
    ASSERT_TRUE(b.scan(3, b3));
    ASSERT_TRUE(c.scan(3, c3));
    ASSERT_GT(a3.cloud.size(), 5000u);
    ASSERT_EQ(a3.cloud.size(), b3.cloud.size());
    for (std::size_t k = 0; k < a3.cloud.size(); ++k) {
        ASSERT_EQ(a3.cloud.points[k], b3.cloud.points[k]);
        ASSERT_EQ(a3.cloud.intensity[k], b3.cloud.intensity[k]);
        ASSERT_EQ(a3.labels[k], b3.labels[k]);
    }
    EXPECT_TRUE(a3.T_world_lidar.isApprox(b3.T_world_lidar));
    // Another seed is another world and other noise.
    bool differs = a3.cloud.size() != c3.cloud.size();
    for (std::size_t k = 0; !differs && k < a3.cloud.size(); ++k)
        differs = a3.cloud.points[k] != c3.cloud.points[k];
    EXPECT_TRUE(differs);
    EXPECT_FALSE(a.scan(a.num_scans(), a3));
}

TEST(Simulator, StaticPointsLieOnTheTruthMesh) {
    ScenarioConfig sc = small_world(5);
    sc.sensor.range_noise = 0.0;
    const Simulator sim(sc);
    const common::PlyMesh truth = sim.truth_mesh();
    SimScan scan;
    ASSERT_TRUE(sim.scan(10, scan));
    ASSERT_EQ(scan.labels.size(), scan.cloud.size());
    ASSERT_EQ(scan.rings.size(), scan.cloud.size());
    int checked = 0;
    for (std::size_t k = 0; k < scan.cloud.size(); k += 97) {
        if (common::label_class(scan.labels[k]) == common::kSimMovingActor) continue;
        const Eigen::Vector3d p = scan.T_world_lidar * scan.cloud.points[k].cast<double>();
        EXPECT_LT(distance_to_mesh(truth, p), 5e-3) << "point " << k;
        ++checked;
    }
    EXPECT_GT(checked, 50);
}

TEST(Simulator, MotionDistortionFollowsThePulseTime) {
    ScenarioConfig sc = small_world(5);
    sc.sensor.range_noise = 0.0;
    sc.sensor.motion_distortion = true;
    sc.sessions[0].route.speed = 8.0;  // 0.8 m a sweep
    const Simulator sim(sc);
    const common::PlyMesh truth = sim.truth_mesh();
    SimScan scan;
    ASSERT_TRUE(sim.scan(4, scan));
    ASSERT_TRUE(scan.cloud.has_time());
    int checked = 0;
    for (std::size_t k = 0; k < scan.cloud.size(); k += 131) {
        if (common::label_class(scan.labels[k]) == common::kSimMovingActor) continue;
        const Eigen::Vector3d p =
            sim.pose_at(4, scan.cloud.time[k]) * scan.cloud.points[k].cast<double>();
        EXPECT_LT(distance_to_mesh(truth, p), 0.03) << "point " << k;  // pose steps of period / 128
        ++checked;
    }
    EXPECT_GT(checked, 30);
    // Without distortion a scan is a snapshot at its stamp: no per-point times to de-skew with.
    sc.sensor.motion_distortion = false;
    SimScan still;
    ASSERT_TRUE(Simulator(sc).scan(4, still));
    EXPECT_FALSE(still.cloud.has_time());
}

// A sweep taken while turning on the spot at 180 deg/s: each point put at the pose of its own
// time lies on the true surface (18 deg of turn within the sweep).
TEST(Simulator, MotionDistortionThroughATurnOnTheSpot) {
    ScenarioConfig sc = small_world(5);
    sc.sensor.range_noise = 0.0;
    sc.sensor.motion_distortion = true;
    sc.sessions[0].route.waypoints = {{2, 10}, {15, 10}, {28, 10}};
    sc.sessions[0].route.waypoints[1].spin_deg = -360;
    sc.sessions[0].route.waypoints[1].spin_time = 2;
    const Simulator sim(sc);
    const common::PlyMesh truth = sim.truth_mesh();
    const std::size_t i = 40;  // 4.0 s: 0.75 s into the turn, which starts at 13 m / 4 m/s
    const double turn =
        Eigen::AngleAxisd(sim.pose(i).linear().transpose() * sim.pose_at(i, 0.099).linear())
            .angle();
    EXPECT_NEAR(turn * 180.0 / M_PI, 17.8, 0.1);
    SimScan scan;
    ASSERT_TRUE(sim.scan(i, scan));
    ASSERT_TRUE(scan.cloud.has_time());
    int checked = 0;
    for (std::size_t k = 0; k < scan.cloud.size(); k += 97) {
        if (common::label_class(scan.labels[k]) == common::kSimMovingActor) continue;
        const Eigen::Vector3d p =
            sim.pose_at(i, scan.cloud.time[k]) * scan.cloud.points[k].cast<double>();
        // pose steps of period / 128: 0.07 deg of turn at most
        const double range = scan.cloud.points[k].norm();
        EXPECT_LT(distance_to_mesh(truth, p), 0.0013 * range + 0.03) << "point " << k;
        ++checked;
    }
    EXPECT_GT(checked, 30);
}

TEST(Simulator, MovingActorPointsAreLabelledAndOnTheActor) {
    ScenarioConfig sc = small_world(9);
    sc.sensor.range_noise = 0.0;
    const Simulator sim(sc);
    ASSERT_EQ(sim.actors().size(), 1u);
    const Actor& walker = sim.actors()[0];
    const Eigen::AlignedBox3f box = sim.world().prototype_mesh(0).bounds();
    std::size_t moving = 0, inside_unlabelled = 0;
    SimScan scan;
    for (std::size_t i = 0; i < sim.num_scans(); i += 3) {
        ASSERT_TRUE(sim.scan(i, scan));
        const Eigen::Isometry3d T_actor_world =
            walker.pose_at(scan.cloud.stamp, sim.terrain()).inverse();
        for (std::size_t k = 0; k < scan.cloud.size(); ++k) {
            const Eigen::Vector3f q =
                (T_actor_world * scan.T_world_lidar * scan.cloud.points[k].cast<double>())
                    .cast<float>();
            const bool in_box = box.exteriorDistance(q) < 0.01f;
            const bool labelled = common::label_class(scan.labels[k]) == common::kSimMovingActor;
            if (labelled) {
                ++moving;
                EXPECT_TRUE(in_box) << "scan " << i << " point " << k;
                EXPECT_EQ(common::label_object_id(scan.labels[k]), walker.id());
            } else if (in_box && q.z() > 0.1f) {
                ++inside_unlabelled;
            }
        }
    }
    EXPECT_GT(moving, 100u);
    EXPECT_EQ(inside_unlabelled, 0u);
}

TEST(Simulator, RobotStandsOnTheTerrain) {
    const Simulator sim(small_world(3));
    for (std::size_t i = 0; i < sim.num_scans(); i += 7) {
        const Eigen::Vector3d p = sim.pose(i).translation();
        const double ground = sim.terrain().height(p.x(), p.y());
        EXPECT_NEAR(p.z() - ground, sim.scenario().sensor.height, 0.02);
        EXPECT_GT(sim.pose(i).linear()(2, 2), 0.99);  // upright on gentle slopes
    }
    EXPECT_NEAR(sim.stamp(1) - sim.stamp(0), 0.1, 1e-9);
}

TEST(Simulator, KidnapsAndSessionTimes) {
    const ScenarioConfig sc =
        load_scenario(LTM_SOURCE_DIR "/components/simulator/scenarios/tiny_loop.yaml");
    const Simulator s0(sc, 0), s1(sc, 1);
    EXPECT_FALSE(s0.after_kidnap(0));
    EXPECT_TRUE(s1.after_kidnap(0));  // kidnapped start
    std::size_t kidnaps = 0;
    for (std::size_t i = 1; i < s1.num_scans(); ++i) {
        EXPECT_GT(s1.stamp(i), s1.stamp(i - 1));
        if (s1.after_kidnap(i)) {
            ++kidnaps;
            EXPECT_GE(s1.stamp(i) - s1.stamp(i - 1), 2.0);  // the pause
            EXPECT_GT((s1.pose(i).translation() - s1.pose(i - 1).translation()).norm(), 3.0);
        }
    }
    EXPECT_EQ(kidnaps, 1u);
    EXPECT_GE(s1.stamp(0), 259200.0);
    EXPECT_THROW(Simulator(sc, 2), ScenarioError);
}

// Laps: a route that ends heading east at (10, 0), east of its start (-10, 0) heading east, so
// the leg back reverses the heading at both ends (as in site_loop.yaml).
TEST(Simulator, LapsRepeatTheRouteThroughDrivableTurns) {
    ScenarioConfig sc = small_world(5);
    sc.sessions[0].actors.placed.clear();
    RouteConfig& route = sc.sessions[0].route;
    route.waypoints = {{-10, 0, 0}, {0, 0, 0}, {0, 15, 0}, {5, 15, 0}, {5, 0, 0}, {10, 0, 0}};
    route.speed = 2.0;
    route.corner_radius = 2.0;
    route.laps = 3;
    const std::vector<Waypoint> w = route_laps(route);
    const std::size_t lap = 6 + 8;  // two turning loops of 4 points each
    ASSERT_EQ(w.size(), 3 * 6 + 2 * 8);
    for (std::size_t k = 0; k < 3; ++k) {
        for (std::size_t i = 0; i < 6; ++i) {
            EXPECT_EQ(w[k * lap + i].x, route.waypoints[i].x);
            EXPECT_EQ(w[k * lap + i].y, route.waypoints[i].y);
        }
    }
    RouteConfig single = route;
    single.laps = 1;
    const RobotPath one(single, "."), three(route, ".");
    EXPECT_GT(three.duration(), 3 * one.duration());
    // Lap 2 starts where lap 1 did (within the corner rounding there), heading the same way.
    const double t2 = three.waypoint_time(static_cast<int>(lap));
    EXPECT_LT((three.plan_position(t2) - Eigen::Vector2d(-10, 0)).norm(), 0.2);
    EXPECT_GT(three.plan_position(t2 + 1.0).x(), -10.0 + 1.5);
    // Drivable: the step between scans never exceeds the speed, the heading turns no faster
    // than on a corner of the route's radius (reversing on the spot would turn 180 deg at once).
    const Simulator sim(sc);
    const double dt = 1.0 / sc.sensor.rate_hz;
    std::size_t starts = 0;  // eastward passes of x = -5: once a lap, on the first leg
    for (std::size_t i = 1; i < sim.num_scans(); ++i) {
        const Eigen::Isometry3d a = sim.pose(i - 1), b = sim.pose(i);
        // (1 % for the sensor riding on the ground normal of the gentle terrain)
        ASSERT_LE((b.translation() - a.translation()).head<2>().norm(), 1.01 * 2.0 * dt);
        const double turn = Eigen::AngleAxisd(a.linear().transpose() * b.linear()).angle();
        ASSERT_LE(turn, 1.5 * 2.0 * dt / 2.0) << "scan " << i;  // 1.5 x speed / radius
        starts += a.translation().x() < -5 && b.translation().x() >= -5;
    }
    EXPECT_EQ(starts, 3u);
}

// The site is the same however often the route is driven: a 3-lap world holds the objects of
// the 1-lap world where they were (only the legs between laps are cleared), so another
// day's scans of the site match a many-lap map of it. (Shaped by all laps, the world was drawn
// anew: every object after the route's equipment elsewhere.)
TEST(Simulator, LapsLeaveTheSiteAsOneLapDoes) {
    ScenarioConfig sc = small_world(5);
    sc.world.margin = 40;
    sc.world.tree_density = 8.0;
    RouteConfig& route = sc.sessions[0].route;
    route.waypoints = {{-10, 10, 0}, {0, 10, 0}, {0, 2, 0}, {20, 2, 0}, {20, 10, 0}, {30, 10, 0}};
    route.speed = 4.0;
    route.corner_radius = 2.0;
    const Simulator one(sc);
    route.laps = 3;
    const Simulator three(sc);
    const auto same = [](const ObjectInstance& a, const ObjectInstance& b) {
        return a.kind == b.kind && a.x == b.x && a.y == b.y && a.yaw == b.yaw && a.size == b.size &&
               a.seed == b.seed && a.base_z == b.base_z;
    };
    const auto in = [&](const ObjectInstance& o, const std::vector<ObjectInstance>& world) {
        return std::any_of(world.begin(), world.end(),
                           [&](const ObjectInstance& w) { return same(o, w); });
    };
    // Where only the 3-lap robot drives: the legs between laps and their turning loops.
    RouteConfig single = route;
    single.laps = 1;
    const RobotPath one_path(single, "."), three_path(route, ".");
    const Points2& lap = one_path.centerline().points();
    Points2 loops;
    for (const Eigen::Vector2d& p : three_path.centerline().points()) {
        const bool on_lap = std::any_of(
            lap.begin(), lap.end(), [&](const Eigen::Vector2d& q) { return (p - q).norm() < 1.0; });
        if (!on_lap) loops.push_back(p);
    }
    ASSERT_FALSE(loops.empty());
    const auto near_loops = [&](const ObjectInstance& o) {
        return std::any_of(loops.begin(), loops.end(), [&](const Eigen::Vector2d& p) {
            return (p - Eigen::Vector2d(o.x, o.y)).norm() < 15.0;
        });
    };
    ASSERT_GT(one.objects().size(), 40u);
    std::size_t kept = 0;
    for (const ObjectInstance& o : one.objects()) {
        const bool there = in(o, three.objects());
        kept += there;
        EXPECT_TRUE(there || near_loops(o))
            << "a 1-lap object at " << o.x << ", " << o.y << " is not in the 3-lap world";
    }
    for (const ObjectInstance& o : three.objects()) {
        EXPECT_TRUE(in(o, one.objects()) || near_loops(o))
            << "a 3-lap object at " << o.x << ", " << o.y << " is not in the 1-lap world";
    }
    // What the legs between laps clear (and what that frees or blocks nearby) is all that changes.
    EXPECT_GE(double(kept), 0.9 * double(one.objects().size()))
        << kept << " of " << one.objects().size() << " objects kept";
}

// Turns on the spot: a full turn left in 4 s on the way east, then a quarter turn left in 1 s
// at a corner, which stays sharp (corner_radius would otherwise round it).
TEST(Simulator, TurnsOnTheSpotKeepTheRobotInPlace) {
    RouteConfig route;
    route.speed = 2.0;
    route.corner_radius = 3.0;
    route.waypoints = {{0, 0}, {10, 0}, {20, 0}, {20, 10}};
    route.waypoints[1].spin_deg = 360;
    route.waypoints[1].spin_time = 4;
    route.waypoints[2].spin_deg = 90;
    route.waypoints[2].spin_time = 1;
    const RobotPath path(route, ".");
    TerrainConfig level;
    level.amplitude = 0.0;
    const Terrain flat(level, Eigen::AlignedBox2d(Eigen::Vector2d(-5, -5), Eigen::Vector2d(25, 15)),
                       1);
    const auto yaw_deg = [&](double t) {
        const Eigen::Matrix3d R = path.pose_at(t, flat, 1.0).linear();
        return std::atan2(R(1, 0), R(0, 0)) * 180.0 / M_PI;
    };
    const auto at = [&](double t) -> Eigen::Vector3d {
        return path.pose_at(t, flat, 1.0).translation();
    };
    EXPECT_DOUBLE_EQ(path.duration(), 15.0 + 5.0);
    EXPECT_DOUBLE_EQ(path.waypoint_time(1), 5.0);
    EXPECT_DOUBLE_EQ(path.waypoint_time(2), 14.0);
    EXPECT_DOUBLE_EQ(path.waypoint_time(3), 20.0);
    for (const double t : {5.0, 6.0, 7.5, 9.0}) {
        EXPECT_NEAR((at(t) - Eigen::Vector3d(10, 0, 1)).norm(), 0.0, 1e-9) << t;
    }
    EXPECT_NEAR(yaw_deg(4.9), 0.0, 1e-9);
    EXPECT_NEAR(yaw_deg(6.0), 90.0, 1e-9);
    EXPECT_NEAR(std::abs(yaw_deg(7.0)), 180.0, 1e-9);
    EXPECT_NEAR(yaw_deg(8.0), -90.0, 1e-9);
    EXPECT_NEAR(yaw_deg(9.5), 0.0, 1e-9);
    EXPECT_NEAR(at(9.5).x(), 11.0, 1e-9);
    // The corner at (20, 0) is driven sharp, then turned on the spot.
    EXPECT_NEAR(at(13.9).y(), 0.0, 1e-9);
    EXPECT_NEAR(at(13.9).x(), 19.8, 1e-9);
    EXPECT_NEAR(yaw_deg(13.9), 0.0, 1e-9);
    EXPECT_NEAR(yaw_deg(14.5), 45.0, 1e-9);
    EXPECT_NEAR((at(14.5) - Eigen::Vector3d(20, 0, 1)).norm(), 0.0, 1e-9);
    EXPECT_NEAR(yaw_deg(15.5), 90.0, 1e-9);
    EXPECT_NEAR((at(15.5) - Eigen::Vector3d(20, 1, 1)).norm(), 0.0, 1e-9);
    // Continuous: never faster than the speed or the rate of the quicker turn (90 deg/s).
    const double dt = 0.01;
    for (double t = dt; t <= path.duration(); t += dt) {
        const Eigen::Isometry3d a = path.pose_at(t - dt, flat, 1.0), b = path.pose_at(t, flat, 1.0);
        ASSERT_LE((b.translation() - a.translation()).norm(), 2.0 * dt + 1e-9) << t;
        ASSERT_LE(Eigen::AngleAxisd(a.linear().transpose() * b.linear()).angle(),
                  M_PI / 2 * dt + 1e-9)
            << t;
    }
    // Turned the other way round: three quarters to the right.
    route.waypoints[2].spin_deg = -270;
    route.waypoints[2].spin_time = 3;
    const RobotPath right(route, ".");
    const Eigen::Matrix3d R = right.pose_at(15.0, flat, 1.0).linear();
    EXPECT_NEAR(std::atan2(R(1, 0), R(0, 0)) * 180.0 / M_PI, -90.0, 1e-9);
}

TEST(Simulator, MissingTrajectoryFileIsOneLine) {
    ScenarioConfig sc = small_world(1);
    sc.sessions[0].route.waypoints.clear();
    sc.sessions[0].route.poses_file = "no/such/poses.txt";
    sc.sessions[0].route.times_file = "no/such/times.txt";
    sc.sessions[0].route.camera_frame = false;
    sc.base_dir = "/tmp";
    try {
        Simulator sim(sc);
        FAIL();
    } catch (const ScenarioError& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("/tmp/no/such/poses.txt"), std::string::npos) << m;
        EXPECT_EQ(m.find('\n'), std::string::npos) << m;
    }
}

TEST(Simulator, FollowsKittiPosesWhenPresent) {
    const std::string data = LTM_SOURCE_DIR "/../shared/data/kitti";
    ScenarioConfig sc = small_world(1);
    sc.world.style = WorldStyle::kTown;
    sc.world.margin = 20;
    sc.world.road_width = 3.2;
    sc.sessions[0].actors.placed.clear();
    RouteConfig& r = sc.sessions[0].route;
    r.waypoints.clear();
    r.poses_file = data + "/sequences/00/poses_semantickitti.txt";
    r.times_file = data + "/sequences/00/times.txt";
    r.calib_file = data + "/sequences/00/calib.txt";
    try {
        const Simulator sim(sc);
        EXPECT_EQ(sim.num_scans(), 4541u);
        // Tr^-1 P0 Tr = I (P0 = I), then moved vertically onto the fitted ground.
        EXPECT_TRUE(sim.pose(0).linear().isApprox(Eigen::Matrix3d::Identity(), 1e-6));
        EXPECT_NEAR(sim.pose(0).translation().head<2>().norm(), 0.0, 1e-6);
        EXPECT_NEAR(sim.stamp(1), 0.1037359, 1e-6);  // the file's times
        for (const std::size_t i : {0u, 100u, 2000u, 4400u}) {
            const Eigen::Vector3d g = sim.pose(i) * Eigen::Vector3d(0, 0, -sc.sensor.height);
            EXPECT_NEAR(g.z(), sim.terrain().height(g.x(), g.y()), 1e-3);
        }
    } catch (const ScenarioError& e) {
        GTEST_SKIP() << "shared KITTI data not here: " << e.what();
    }
}

}  // namespace
}  // namespace ltm::sim
