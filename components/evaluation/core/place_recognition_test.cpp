#include "evaluation/core/place_recognition.hpp"

#include <gtest/gtest.h>

namespace ltm::eval {
namespace {

common::PoseList along_x(const std::vector<double>& xs) {
    common::PoseList out;
    for (double x : xs) {
        Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
        T.translation().x() = x;
        out.push_back(T);
    }
    return out;
}

// Out along x for frames 0..59 (x = i), back for frames 60..119 (x = 119 - i).
common::PoseList out_and_back() {
    std::vector<double> xs;
    for (int i = 0; i < 120; ++i) xs.push_back(i < 60 ? i : 119 - i);
    return along_x(xs);
}

TEST(PlaceRecognition, HandComputedSingleSession) {
    // Revisit queries (radius 5 m, gap 50 frames): frame q >= 60 at x = 119 - q needs an
    // earlier frame j <= q - 50 with |j - (119 - q)| <= 5, i.e. 114 - q <= q - 50: q >= 82.
    // So q = 82..119: 38 queries.
    const std::vector<LoopPair> loops = {
        {100, 19, 0.9},  // x 19 vs 19: true
        {90, 35, 0.8},   // x 29 vs 35: 6 m, false
        {9, 110, 0.7},   // reversed order, x 9 vs 9: true
        {105, 10, 0.6},  // x 14 vs 10: 4 m, true
        {100, 18, 0.5},  // true, same query as the first
        {65, 60, 0.4},   // 5 frames apart: trivial, excluded
        {200, 3, 0.3},   // no such frame: excluded
    };
    const PlaceRecognitionResult r = evaluate_loops(loops, out_and_back());
    EXPECT_EQ(r.true_positives, 4u);
    EXPECT_EQ(r.false_positives, 1u);
    EXPECT_EQ(r.trivial, 1u);
    EXPECT_EQ(r.out_of_range, 1u);
    EXPECT_EQ(r.revisit_queries, 38u);
    EXPECT_EQ(r.recalled_queries, 3u);
    EXPECT_DOUBLE_EQ(r.precision, 0.8);
    EXPECT_DOUBLE_EQ(r.recall, 3.0 / 38.0);
    EXPECT_DOUBLE_EQ(r.f1, 2 * 0.8 * (3.0 / 38.0) / (0.8 + 3.0 / 38.0));
    EXPECT_EQ(r.correct, (std::vector<bool>{true, false, true, true, true, false, false}));
}

TEST(PlaceRecognition, HandComputedCrossSession) {
    // Query session at x = 0, 10, 20; match session at x = 0.5, 30. Only query 0 has a revisit.
    const std::vector<LoopPair> loops = {{0, 0, 0}, {1, 0, 0}, {2, 1, 0}};
    const PlaceRecognitionResult r =
        evaluate_cross_session_loops(loops, along_x({0, 10, 20}), along_x({0.5, 30}));
    EXPECT_EQ(r.true_positives, 1u);
    EXPECT_EQ(r.false_positives, 2u);
    EXPECT_EQ(r.revisit_queries, 1u);
    EXPECT_DOUBLE_EQ(r.precision, 1.0 / 3.0);
    EXPECT_DOUBLE_EQ(r.recall, 1.0);
    EXPECT_DOUBLE_EQ(r.f1, 0.5);
}

TEST(PlaceRecognition, NoLoopsNoRevisits) {
    const PlaceRecognitionResult r = evaluate_loops({}, along_x({0, 10, 20}));
    EXPECT_EQ(r.revisit_queries, 0u);
    EXPECT_DOUBLE_EQ(r.f1, 0.0);
}

}  // namespace
}  // namespace ltm::eval
