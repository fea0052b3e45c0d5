#include "registration/core/loop_verifier.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>

#include "registration/core/test_data.hpp"

namespace ltm::registration {
namespace {

constexpr double kDeg = M_PI / 180.0;

double rot_deg(const Eigen::Isometry3d& T) { return Eigen::AngleAxisd(T.linear()).angle() / kDeg; }

// A map of frames [first, last] of the snippet, anchored at frame `first` (reference poses).
common::LocalMapData kitti_map(const test::KittiSnippet& s, std::size_t first, std::size_t last,
                               std::uint64_t id) {
    std::vector<std::vector<Eigen::Vector3f>> scans;
    common::PoseList poses;
    for (std::size_t i = first; i <= last; ++i) {
        scans.push_back(test::every_nth(s.scans[i].points, 2, 0));
        poses.push_back(s.poses[i]);
    }
    return test::build_local_map(id, s.poses[first], scans, poses);
}

TEST(LoopVerifier, RealKittiRevisitInTheOppositeDirection) {
    const std::string dir = test::shared_kitti00();
    if (dir.empty()) GTEST_SKIP() << "KITTI 00 frames 0-15 not found under ../shared/data/kitti";
    const test::KittiSnippet s = test::load_kitti(dir, 16);
    const common::LocalMapData map = kitti_map(s, 0, 7, 0);
    LoopVerifier verifier{LoopVerifierConfig()};
    const Eigen::Isometry3d turn = test::xy_yaw(0, 0, 180.0);
    // The query: frame q seen by a sensor turned round (odd points; the map has the even ones),
    // from a guess up to 6 m and 10 deg off (a Scan Context candidate's pose and yaw).
    for (const std::size_t q : {3, 7, 10, 12}) {
        const std::vector<Eigen::Vector3f> pts =
            test::transformed(test::every_nth(s.scans[q].points, 2, 1), turn.inverse());
        const Eigen::Isometry3d truth = s.poses[0].inverse() * s.poses[q] * turn;
        for (const double dx : {0.0, 3.0, 6.0}) {
            const LoopVerification v =
                verifier.verify(pts, 0, map, truth * test::xy_yaw(dx, 0.5, dx > 5 ? -10.0 : 5.0));
            EXPECT_TRUE(v.accepted)
                << "frame " << q << " dx " << dx << ": " << v.reason << " structure "
                << v.structure_inliers << "/" << v.structure_points;
            const Eigen::Isometry3d err = truth.inverse() * v.T_anchor_lidar;
            EXPECT_LT(err.translation().norm(), 0.06) << "frame " << q << " dx " << dx;
            EXPECT_LT(rot_deg(err), 0.2) << "frame " << q << " dx " << dx;
            EXPECT_GT(v.inlier_fraction, 0.6);
        }
    }
}

TEST(LoopVerifier, RealKittiScansOfOtherPlacesAreRefused) {
    const std::string dir = test::shared_kitti00();
    if (dir.empty()) GTEST_SKIP() << "KITTI 00 frames 0-15 not found under ../shared/data/kitti";
    const test::KittiSnippet s = test::load_kitti(dir, 16);
    const common::LocalMapData map = kitti_map(s, 0, 7, 0);
    LoopVerifier verifier{LoopVerifierConfig()};
    int tried = 0;
    for (const char* seq : {"04", "05", "07"}) {
        const test::KittiSnippet other = test::load_kitti(dir + "/../" + seq, 1);
        if (other.scans.empty()) continue;
        for (const double yaw : {0.0, 90.0, 180.0, 270.0}) {
            const Eigen::Isometry3d guess =
                s.poses[0].inverse() * s.poses[3] * test::xy_yaw(0, 0, yaw);
            const LoopVerification v = verifier.verify(other.scans[0].points, 0, map, guess);
            EXPECT_FALSE(v.accepted) << "sequence " << seq << " yaw " << yaw << " accepted with "
                                     << v.inliers << " inliers (" << v.inlier_fraction << ")";
            EXPECT_FALSE(v.reason.empty());
            ++tried;
        }
    }
    EXPECT_EQ(tried, 12);
}

TEST(LoopVerifier, SyntheticOtherSceneIsRefusedAndBadInputExplained) {
    const std::vector<Eigen::Vector3f> scene = test::synthetic_scene(41),
                                       other = test::synthetic_scene(42);
    const Eigen::Isometry3d anchor = test::xy_yaw(0, 0, 0);
    const common::LocalMapData map =
        test::build_local_map(1, anchor, {test::view(scene, anchor, 50.0)}, {anchor}, 1.0, 50.0);
    LoopVerifier verifier{LoopVerifierConfig()};
    EXPECT_FALSE(verifier.verify(test::view(other, anchor, 50.0), 1, map, anchor).accepted);
    Eigen::Isometry3d nan_guess = anchor;
    nan_guess.translation().x() = std::nan("");
    EXPECT_NE(verifier.verify(test::view(scene, anchor, 50.0), 1, map, nan_guess)
                  .reason.find("not finite"),
              std::string::npos);
    EXPECT_NE(verifier.verify({}, 1, map, anchor).reason.find("points"), std::string::npos);
    EXPECT_NE(verifier.verify(test::view(scene, anchor, 50.0), 2, common::LocalMapData(), anchor)
                  .reason.find("no voxels"),
              std::string::npos);
    LoopVerifierConfig bad;
    bad.min_inlier_fraction = 1.5;
    try {
        LoopVerifier refused{bad};
        ADD_FAILURE() << "min_inlier_fraction 1.5 accepted";
    } catch (const common::ConfigError& e) {
        EXPECT_STREQ(e.what(), "verification.min_inlier_fraction: must be in [0, 1] (got 1.5)");
    }
    bad = LoopVerifierConfig();
    bad.yaw_offsets.clear();
    EXPECT_EQ(validate(bad)->key, "yaw_offsets");
    bad = LoopVerifierConfig();
    bad.fine.max_iterations = 0;  // the registration's own rules hold for both passes
    EXPECT_EQ(validate(bad)->key, "fine.max_iterations");
    bad = LoopVerifierConfig();
    bad.max_correction_translation = std::numeric_limits<double>::infinity();  // no limit
    EXPECT_FALSE(validate(bad));
}

TEST(LoopVerifier, SeveralGuessesAreTriedInOrderUntilOneIsAccepted) {
    const std::vector<Eigen::Vector3f> scene = test::with_dense_ground(test::synthetic_scene(43));
    const Eigen::Isometry3d anchor = test::xy_yaw(0, 0, 0);
    const common::LocalMapData map =
        test::build_local_map(1, anchor, {test::view(scene, anchor, 50.0)}, {anchor}, 1.0, 50.0);
    const Eigen::Isometry3d truth = test::xy_yaw(3.0, -2.0, 20.0);
    const std::vector<Eigen::Vector3f> pts = test::view(scene, truth, 50.0);
    LoopVerifier verifier{LoopVerifierConfig()};
    // Far outside any basin (and beyond max_correction_translation): refused on its own.
    const Eigen::Isometry3d far = truth * test::xy_yaw(15.0, 0.0, 90.0);
    const Eigen::Isometry3d near = truth * test::xy_yaw(0.4, 0.3, 2.0);
    EXPECT_FALSE(verifier.verify(pts, 1, map, far).accepted);
    for (const bool far_first : {true, false}) {
        const GuessList guesses = far_first ? GuessList{far, near} : GuessList{near, far};
        const LoopVerification v = verifier.verify(pts, 1, map, guesses);
        ASSERT_TRUE(v.accepted) << v.reason;
        EXPECT_EQ(v.guess, far_first ? 1u : 0u);
        const Eigen::Isometry3d err = truth.inverse() * v.T_anchor_lidar;
        EXPECT_LT(err.translation().norm(), 0.05);
        EXPECT_LT(rot_deg(err), 0.2);
    }
    EXPECT_NE(verifier.verify(pts, 1, map, GuessList{}).reason.find("no initial guess"),
              std::string::npos);
}

TEST(LoopVerifier, FineOnlyFromANearGuessAgreesWithBothPassesAndFailsFromAFarOne) {
    const std::vector<Eigen::Vector3f> scene = test::with_dense_ground(test::synthetic_scene(43));
    const Eigen::Isometry3d anchor = test::xy_yaw(0, 0, 0);
    const common::LocalMapData map =
        test::build_local_map(1, anchor, {test::view(scene, anchor, 50.0)}, {anchor}, 1.0, 50.0);
    const RegistrationTarget target = make_registration_target(map, 0.4, 3);
    const Eigen::Isometry3d truth = test::xy_yaw(3.0, -2.0, 20.0);
    const std::vector<Eigen::Vector3f> pts = test::view(scene, truth, 50.0);
    LoopVerifier verifier{LoopVerifierConfig()};
    const GuessList near{truth * test::xy_yaw(0.2, -0.15, 1.0)};
    const LoopVerification both = verifier.verify(pts, target, near);
    const LoopVerification fine =
        verifier.verify(pts, target, near, LoopVerifier::Passes::kFineOnly);
    ASSERT_TRUE(both.accepted) << both.reason;
    ASSERT_TRUE(fine.accepted) << fine.reason;
    EXPECT_LT((both.T_anchor_lidar.inverse() * fine.T_anchor_lidar).translation().norm(), 0.01);
    EXPECT_LT((truth.inverse() * fine.T_anchor_lidar).translation().norm(), 0.05);
    EXPECT_LT(fine.iterations, both.iterations);  // the coarse pass was left out
    // The fit's constraints come with it: a positive definite Hessian, a finite covariance.
    EXPECT_GT(Eigen::SelfAdjointEigenSolver<Matrix6d>(fine.hessian).eigenvalues()[0], 0.0);
    EXPECT_TRUE(fine.covariance.allFinite());
    // From 6 m off, the fine pass alone does not reach the truth: refused or elsewhere.
    const GuessList far{truth * test::xy_yaw(6.0, 0.0, 0.0)};
    const LoopVerification f = verifier.verify(pts, target, far, LoopVerifier::Passes::kFineOnly);
    const double off = (truth.inverse() * f.T_anchor_lidar).translation().norm();
    EXPECT_TRUE(!f.accepted || off > 1.0) << off;
}

// A wrong alignment can fit the part of a scan that reaches the map and leave the rest in the
// map's empty space; the structure ratio counts only points that reach a surface, so the share of
// unmatched points is checked on its own (max_unmatched_fraction).
TEST(LoopVerifier, AScanPartlyInTheMapsEmptySpaceIsRefusedWithAnUnmatchedLimit) {
    const std::vector<Eigen::Vector3f> scene = test::with_dense_ground(test::synthetic_scene(43));
    const Eigen::Isometry3d anchor = test::xy_yaw(0, 0, 0);
    const common::LocalMapData map =
        test::build_local_map(1, anchor, {test::view(scene, anchor, 50.0)}, {anchor}, 1.0, 50.0);
    const RegistrationTarget target = make_registration_target(map, 0.4, 3);
    const Eigen::Isometry3d truth = test::xy_yaw(3.0, -2.0, 20.0);
    const std::vector<Eigen::Vector3f> clean = test::view(scene, truth, 50.0);
    // The same scan with another scene's nearest 25 m 40 m above it, where the map has nothing
    // (a fifth to a third of the points, once down-sampled, unmatched).
    std::vector<Eigen::Vector3f> half = clean;
    for (const Eigen::Vector3f& p : test::view(test::synthetic_scene(44), anchor, 25.0))
        half.push_back(p + Eigen::Vector3f(0.0f, 0.0f, 40.0f));
    const GuessList near{truth * test::xy_yaw(0.2, -0.15, 1.0)};
    LoopVerifierConfig config;
    config.max_points = 100000;
    LoopVerifier unlimited{config};
    const LoopVerification a = unlimited.verify(half, target, near);
    ASSERT_TRUE(a.accepted) << a.reason;  // no limit: what the structure ratio alone passes
    const double share = double(a.unmatched) / double(a.points);
    EXPECT_GT(share, 0.18) << a.inlier_fraction;
    EXPECT_LT(share, 0.4);

    config.max_unmatched_fraction = 0.15;
    LoopVerifier limited{config};
    const LoopVerification b = limited.verify(half, target, near);
    EXPECT_FALSE(b.accepted);
    EXPECT_NE(b.reason.find("unmatched fraction"), std::string::npos) << b.reason;
    const LoopVerification c = limited.verify(clean, target, near);
    ASSERT_TRUE(c.accepted) << c.reason;
    EXPECT_LT(double(c.unmatched) / double(c.points), 0.15);
    EXPECT_LT((truth.inverse() * c.T_anchor_lidar).translation().norm(), 0.05);
    config.max_unmatched_fraction = 1.5;
    EXPECT_EQ(validate(config)->key, "max_unmatched_fraction");
}

}  // namespace
}  // namespace ltm::registration
