#include "evaluation/core/dynamic_removal.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace ltm::eval {
namespace {

TEST(DynamicRemoval, HandComputedScores) {
    // 4 static and 2 dynamic truth points, 1 m apart.
    LabelledMap truth;
    truth.points = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}, {0, 5, 0}, {1, 5, 0}};
    truth.dynamic = {0, 0, 0, 0, 1, 1};
    // Output: static 0 exact, static 1 moved 3 cm (kept), static 2 moved 6 cm (lost), static 3
    // missing; dynamic 0 still there (not removed), dynamic 1 gone; one extra point.
    const std::vector<Eigen::Vector3f> output = {
        {0, 0, 0}, {1.03f, 0, 0}, {2.06f, 0, 0}, {0, 5, 0}, {50, 50, 50}};
    const DynamicRemovalResult r = evaluate_dynamic_removal(truth, output);
    EXPECT_EQ(r.static_points, 4u);
    EXPECT_EQ(r.static_kept, 2u);
    EXPECT_EQ(r.dynamic_points, 2u);
    EXPECT_EQ(r.dynamic_removed, 1u);
    EXPECT_DOUBLE_EQ(r.sa_pct, 50.0);
    EXPECT_DOUBLE_EQ(r.da_pct, 50.0);
    EXPECT_DOUBLE_EQ(r.aa_pct, 50.0);
    EXPECT_DOUBLE_EQ(r.ha_pct, 50.0);

    // A looser match distance keeps static 2 as well: SA 75, DA 50, AA sqrt(3750), HA 60.
    const DynamicRemovalResult loose = evaluate_dynamic_removal(truth, output, {0.07});
    EXPECT_DOUBLE_EQ(loose.sa_pct, 75.0);
    EXPECT_NEAR(loose.aa_pct, std::sqrt(3750.0), 1e-12);
    EXPECT_NEAR(loose.ha_pct, 60.0, 1e-12);
}

TEST(DynamicRemoval, RawMapKeepsEverythingAndPerfectMapRemovesOnlyDynamics) {
    LabelledMap truth;
    truth.points = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
    truth.dynamic = {0, 1, 0};
    const DynamicRemovalResult raw = evaluate_dynamic_removal(truth, truth.points);
    EXPECT_DOUBLE_EQ(raw.sa_pct, 100.0);
    EXPECT_DOUBLE_EQ(raw.da_pct, 0.0);
    const DynamicRemovalResult perfect = evaluate_dynamic_removal(truth, {{0, 0, 0}, {2, 0, 0}});
    EXPECT_DOUBLE_EQ(perfect.aa_pct, 100.0);
}

TEST(DynamicRemoval, AppendLabelledScanTransformsFiltersAndLabels) {
    common::PointCloud cloud;
    cloud.points = {{1, 0, 0}, {2, 0, 0}, {60, 0, 0}, {3, 0, 0}};
    // SemanticKITTI: 252 moving car with instance id 7 in the high bits; 10 car; 254 person.
    const std::vector<std::uint32_t> labels = {(7u << 16) | 252u, 10u, 254u, 40u};
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = Eigen::Vector3d(0, 0, 10);
    LabelledMap map;
    ASSERT_TRUE(append_labelled_scan(cloud, labels, T, common::LabelScheme::kSemanticKitti, false,
                                     50.0, map));
    ASSERT_EQ(map.points.size(), 3u);  // the 60 m point is beyond max_range
    EXPECT_TRUE(map.points[0].isApprox(Eigen::Vector3f(1, 0, 10)));
    EXPECT_EQ(map.dynamic, (std::vector<std::uint8_t>{1, 0, 0}));
    EXPECT_FALSE(
        append_labelled_scan(cloud, {1u}, T, common::LabelScheme::kSemanticKitti, false, 0, map));
}

TEST(DynamicRemoval, SimulatorLabelEncoding) {
    const std::uint32_t actor = common::make_label(common::kSimMovingActor, 12);
    EXPECT_EQ(common::label_class(actor), common::kSimMovingActor);
    EXPECT_EQ(common::label_object_id(actor), 12);
    EXPECT_TRUE(common::is_dynamic_label(actor, common::LabelScheme::kLtmSim));
    const std::uint32_t changed = common::make_label(common::kSimChangedObject, 3);
    EXPECT_FALSE(common::is_dynamic_label(changed, common::LabelScheme::kLtmSim));
    EXPECT_TRUE(common::is_dynamic_label(changed, common::LabelScheme::kLtmSim, true));
    EXPECT_FALSE(common::is_dynamic_label(common::make_label(common::kSimStatic, 0),
                                          common::LabelScheme::kLtmSim, true));
    EXPECT_FALSE(common::is_dynamic_label(251, common::LabelScheme::kSemanticKitti));
    EXPECT_TRUE(common::is_dynamic_label(259, common::LabelScheme::kSemanticKitti));
    EXPECT_FALSE(common::is_dynamic_label(260, common::LabelScheme::kSemanticKitti));
}

}  // namespace
}  // namespace ltm::eval
