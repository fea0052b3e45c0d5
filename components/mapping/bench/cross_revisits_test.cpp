// The multi-robot benchmark's revisits of the other robot's places: closed by a loop at one of
// their frames, or by a loop joining the local maps at them (not by a loop between other maps).
#include "mapping/bench/cross_revisits.hpp"

#include <gtest/gtest.h>

namespace ltm::mapping::bench {
namespace {

Eigen::Isometry3d at(double x, double y) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = Eigen::Vector3d(x, y, 0.0);
    return T;
}

// Robot A drives along y = 0, one metre a frame, local maps 0 (frames 0-4), 1 (5-14), 2 (15-20);
// robot B stands at (11, 3) in its local map 7: A's frames 9-13 are within 4 m of it.
struct Site {
    common::PoseList a, b;
    std::vector<std::uint64_t> a_maps, b_maps;
    Site() {
        for (int i = 0; i <= 20; ++i) {
            a.push_back(at(i, 0.0));
            b.push_back(at(11.0, 3.0));
            a_maps.push_back(i < 5 ? 0 : i < 15 ? 1 : 2);
            b_maps.push_back(7);
        }
    }
};

TEST(CrossRevisits, ClosedByALoopJoiningTheLocalMapsAtTheRevisit) {
    const Site s;
    std::vector<RevisitSegment> seg = cross_revisit_segments(s.a, s.b, 4.0);
    ASSERT_EQ(seg.size(), 1u);
    EXPECT_EQ(seg[0].first, 9u);
    EXPECT_EQ(seg[0].last, 13u);
    // A loop from A's frame 6 (map 1, outside the segment) to B's frame 0 (map 7).
    mark_closed({6}, &seg);
    EXPECT_FALSE(seg[0].closed);
    mark_closed_by_local_maps(s.a, s.b, s.a_maps, s.b_maps, 4.0, {{6, 0}}, &seg);
    EXPECT_TRUE(seg[0].closed);
}

TEST(CrossRevisits, NotClosedByALoopBetweenOtherLocalMaps) {
    const Site s;
    std::vector<RevisitSegment> seg = cross_revisit_segments(s.a, s.b, 4.0);
    ASSERT_EQ(seg.size(), 1u);
    // A's maps 0 and 2 hold no revisiting frame.
    mark_closed_by_local_maps(s.a, s.b, s.a_maps, s.b_maps, 4.0, {{2, 0}, {18, 5}}, &seg);
    EXPECT_FALSE(seg[0].closed);
    // B's frame in another map of B's (a loop elsewhere): the map at the revisit is not joined.
    std::vector<std::uint64_t> b_maps = s.b_maps;
    b_maps[20] = 8;
    mark_closed_by_local_maps(s.a, s.b, s.a_maps, b_maps, 4.0, {{6, 20}}, &seg);
    EXPECT_FALSE(seg[0].closed);
}

}  // namespace
}  // namespace ltm::mapping::bench
