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
                                     50.0, 4, map));
    ASSERT_EQ(map.points.size(), 3u);  // the 60 m point is beyond max_range
    EXPECT_TRUE(map.points[0].isApprox(Eigen::Vector3f(1, 0, 10)));
    EXPECT_EQ(map.dynamic, (std::vector<std::uint8_t>{1, 0, 0}));
    EXPECT_EQ(map.labels, (std::vector<std::uint32_t>{(7u << 16) | 252u, 10u, 40u}));
    EXPECT_EQ(map.frames, (std::vector<std::uint32_t>{4, 4, 4}));
    EXPECT_FALSE(append_labelled_scan(cloud, {1u}, T, common::LabelScheme::kSemanticKitti, false, 0,
                                      5, map));
    EXPECT_EQ(map.labels.size(), 3u);
}

// Four SemanticKITTI scans from a sensor driving 5 m a frame along y. Object 5 (moving car)
// travels 3 m along x in the world (its sensor-frame centroid moves much more), object 9 travels
// 0.2 m; a person also numbered 5 is another object (SemanticKITTI numbers instances per class);
// a person and a bicyclist carry no instance id. The output map keeps every static point, none of
// car 5, and every other dynamic point.
struct TwoObjects {
    LabelledMap truth;
    std::vector<Eigen::Vector3f> output;
};

TwoObjects two_objects() {
    const auto label = [](std::uint16_t cls, std::uint16_t id) {
        return common::make_label(cls, id);
    };
    // World positions per frame: {point, label}.
    std::vector<std::vector<std::pair<Eigen::Vector3f, std::uint32_t>>> world(4);
    for (std::uint32_t k = 0; k < 4; ++k) {
        const float x = 10.0f + static_cast<float>(k);  // object 5's centroid: x = 10 .. 13
        for (const Eigen::Vector3f& d : {Eigen::Vector3f(0.1f, 0, 0), Eigen::Vector3f(-0.1f, 0, 0),
                                         Eigen::Vector3f(0, 0.1f, 0), Eigen::Vector3f(0, -0.1f, 0)})
            world[k].push_back({Eigen::Vector3f(x, 0, 0) + d, label(252, 5)});
        // Static points, one of them a parked car that shares object 5's instance id.
        world[k].push_back({Eigen::Vector3f(0, 3.0f * static_cast<float>(k), -1.5f), label(40, 0)});
        world[k].push_back({Eigen::Vector3f(5, 3.0f * static_cast<float>(k), 0), label(10, 5)});
    }
    for (std::uint32_t k : {1u, 3u}) {  // object 9: centroid x = 20 in frame 1, 20.2 in frame 3
        const float x = k == 1 ? 20.0f : 20.2f;
        world[k].push_back({Eigen::Vector3f(x, 1, 0), label(252, 9)});
        world[k].push_back({Eigen::Vector3f(x, -1, 0), label(252, 9)});
    }
    world[0].push_back({Eigen::Vector3f(30, 5, 0), label(254, 0)});  // a person, 0.5 m
    world[2].push_back({Eigen::Vector3f(30, 5.5f, 0), label(254, 0)});
    world[1].push_back({Eigen::Vector3f(40, 5, 0), label(253, 0)});  // a bicyclist, once
    world[2].push_back({Eigen::Vector3f(50, 0, 0), label(254, 5)});  // person 5, once

    TwoObjects t;
    for (std::uint32_t k = 0; k < 4; ++k) {
        Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
        T.translation() = Eigen::Vector3d(0, 5.0 * k, 0);
        common::PointCloud cloud;
        std::vector<std::uint32_t> labels;
        for (const auto& [p, l] : world[k]) {
            cloud.points.push_back(T.inverse().cast<float>() * p);
            labels.push_back(l);
            if (l != label(252, 5)) t.output.push_back(p);
        }
        EXPECT_TRUE(append_labelled_scan(cloud, labels, T, common::LabelScheme::kSemanticKitti,
                                         false, 0.0, k, t.truth));
    }
    return t;
}

TEST(DynamicRemoval, PerObjectTravelAndDa) {
    const TwoObjects t = two_objects();
    const DynamicRemovalResult r = evaluate_dynamic_removal(t.truth, t.output);
    // The overall scores are those of the points: 16 of 24 dynamic points removed.
    EXPECT_DOUBLE_EQ(r.sa_pct, 100.0);
    EXPECT_EQ(r.dynamic_points, 24u);
    EXPECT_EQ(r.dynamic_removed, 16u);
    EXPECT_NEAR(r.da_pct, 100.0 * 16.0 / 24.0, 1e-9);

    ASSERT_EQ(r.objects.size(), 5u);
    const DynamicObject& car = r.objects[0];
    EXPECT_EQ(car.instance, 5);
    EXPECT_EQ(car.label_class, 252);
    EXPECT_EQ(car.points, 16u);
    EXPECT_EQ(car.removed, 16u);
    EXPECT_DOUBLE_EQ(car.removed_pct, 100.0);
    EXPECT_EQ(car.first_frame, 0u);
    EXPECT_EQ(car.last_frame, 3u);
    EXPECT_EQ(car.frames, 4u);
    EXPECT_NEAR(car.travel, 3.0, 1e-5);  // world frame, not the sensor's

    const DynamicObject& person = r.objects[1];
    EXPECT_EQ(person.instance, 5);
    EXPECT_EQ(person.label_class, 254);
    EXPECT_EQ(person.points, 1u);
    EXPECT_EQ(person.removed, 0u);
    EXPECT_EQ(person.first_frame, 2u);
    EXPECT_EQ(person.frames, 1u);
    EXPECT_DOUBLE_EQ(person.travel, 0.0);

    const DynamicObject& slow = r.objects[2];
    EXPECT_EQ(slow.instance, 9);
    EXPECT_EQ(slow.points, 4u);
    EXPECT_EQ(slow.removed, 0u);
    EXPECT_EQ(slow.first_frame, 1u);
    EXPECT_EQ(slow.last_frame, 3u);
    EXPECT_EQ(slow.frames, 2u);
    EXPECT_NEAR(slow.travel, 0.2, 1e-5);

    // Points without an instance id: one object per class, after the named ones.
    EXPECT_EQ(r.objects[3].instance, 0);
    EXPECT_EQ(r.objects[3].label_class, 253);
    EXPECT_EQ(r.objects[3].points, 1u);
    EXPECT_DOUBLE_EQ(r.objects[3].travel, 0.0);
    EXPECT_EQ(r.objects[4].instance, 0);
    EXPECT_EQ(r.objects[4].label_class, 254);
    EXPECT_EQ(r.objects[4].points, 2u);
    EXPECT_NEAR(r.objects[4].travel, 0.5, 1e-5);
    EXPECT_EQ(r.objects[4].first_frame, 0u);
    EXPECT_EQ(r.objects[4].last_frame, 2u);

    // Travelling at least 1 m: only object 5, all of it removed.
    EXPECT_EQ(r.moving_objects, 1u);
    EXPECT_EQ(r.moving_points, 16u);
    EXPECT_EQ(r.moving_removed, 16u);
    EXPECT_DOUBLE_EQ(r.moving_da_pct, 100.0);

    // At least 0.1 m: objects 5, 9 and the person; 0.4 m: object 5 and the person; 0: every object.
    const DynamicRemovalResult slow_too = evaluate_dynamic_removal(t.truth, t.output, {0.05, 0.1});
    EXPECT_EQ(slow_too.moving_objects, 3u);
    EXPECT_NEAR(slow_too.moving_da_pct, 100.0 * 16.0 / 22.0, 1e-9);
    const DynamicRemovalResult half = evaluate_dynamic_removal(t.truth, t.output, {0.05, 0.4});
    EXPECT_EQ(half.moving_objects, 2u);
    EXPECT_EQ(half.moving_points, 18u);
    EXPECT_EQ(half.moving_removed, 16u);
    const DynamicRemovalResult all = evaluate_dynamic_removal(t.truth, t.output, {0.05, 0.0});
    EXPECT_EQ(all.moving_objects, 5u);
    EXPECT_NEAR(all.moving_da_pct, r.da_pct, 1e-9);
}

TEST(DynamicRemoval, NoPerObjectViewWithoutLabels) {
    LabelledMap truth;
    truth.points = {{0, 0, 0}, {1, 0, 0}};
    truth.dynamic = {0, 1};
    const DynamicRemovalResult r = evaluate_dynamic_removal(truth, {{0, 0, 0}});
    EXPECT_DOUBLE_EQ(r.da_pct, 100.0);
    EXPECT_TRUE(r.objects.empty());
    EXPECT_EQ(r.moving_objects, 0u);
    EXPECT_DOUBLE_EQ(r.moving_da_pct, 0.0);
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
