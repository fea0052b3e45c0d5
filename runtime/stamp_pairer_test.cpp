#include "runtime/stamp_pairer.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace ltm::runtime {
namespace {

using Pairer = StampPairer<std::string, int>;
using Clock = Pairer::Clock;

struct Out {
    double stamp;
    std::string scan;
    std::optional<int> pose;
};

std::vector<Out> release(Pairer& p, Clock::time_point now = Clock::now()) {
    std::vector<Out> out;
    p.release(
        [&](double t, std::string&& s, std::optional<int>&& pose) {
            out.push_back({t, s, pose});
        },
        now);
    return out;
}

TEST(StampPairerTest, AScanWaitsForThePoseOfItsStamp) {
    Pairer p;
    p.add_scan(1.0, "a");
    EXPECT_TRUE(release(p).empty());
    p.add_pose(1.00005, 7);  // within same_stamp
    const auto out = release(p);
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(out[0].scan, "a");
    EXPECT_EQ(out[0].pose, 7);
}

TEST(StampPairerTest, CountsTheWaitingScansBytes) {
    Pairer p;
    const auto bytes = [](const std::string& s) { return s.size(); };
    EXPECT_EQ(p.waiting_bytes(bytes), 0u);
    p.add_scan(1.0, "abc");
    p.add_scan(2.0, "de");
    const std::size_t two = p.waiting_bytes(bytes);
    EXPECT_GE(two, 5u);
    p.add_pose(1.0, 7);
    ASSERT_EQ(release(p).size(), 1u);            // "de" left
    const std::size_t per_scan = (two - 5) / 2;  // the queue's own record of a scan
    EXPECT_EQ(p.waiting_bytes(bytes), per_scan + 2);
}

TEST(StampPairerTest, PosesBeforeScansPairToo) {
    Pairer p;
    p.add_pose(1.0, 1);
    p.add_pose(2.0, 2);
    p.add_pose(3.0, 3);
    p.add_scan(2.0, "b");
    auto out = release(p);
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(out[0].pose, 2);
    p.add_scan(1.0, "late");  // its pose went with the older ones; a newer one exists
    out = release(p);
    ASSERT_EQ(out.size(), 1u);
    EXPECT_FALSE(out[0].pose.has_value());
}

TEST(StampPairerTest, ANewerPoseReleasesTheScanWithoutOne) {
    Pairer p;
    p.add_scan(1.0, "a");
    p.add_scan(2.0, "b");
    p.add_pose(2.0, 2);
    const auto out = release(p);
    ASSERT_EQ(out.size(), 2u);  // in order: a without, b with
    EXPECT_EQ(out[0].scan, "a");
    EXPECT_FALSE(out[0].pose.has_value());
    EXPECT_EQ(out[1].pose, 2);
}

TEST(StampPairerTest, NoPoseAndTheWaitReleaseTheScan) {
    StampPairerOptions o;
    o.wait_s = 1.0;
    Pairer p(o);
    const auto t0 = Clock::now();
    p.add_scan(1.0, "a", t0);
    p.add_scan(2.0, "b", t0);
    p.add_no_pose(1.0);
    auto out = release(p, t0);
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(out[0].scan, "a");
    EXPECT_TRUE(release(p, t0 + std::chrono::milliseconds(999)).empty());
    out = release(p, t0 + std::chrono::seconds(1));
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(out[0].scan, "b");
    EXPECT_FALSE(out[0].pose.has_value());
}

TEST(StampPairerTest, NoWaitReleasesAtOnce) {
    StampPairerOptions o;
    o.wait_s = 0.0;
    Pairer p(o);
    p.add_scan(1.0, "a");
    const auto out = release(p);
    ASSERT_EQ(out.size(), 1u);
    EXPECT_FALSE(out[0].pose.has_value());
}

TEST(StampPairerTest, BoundsDropTheOldest) {
    StampPairerOptions o;
    o.max_waiting = 2;
    o.max_poses = 2;
    Pairer p(o);
    p.add_scan(1.0, "a");
    p.add_scan(2.0, "b");
    p.add_scan(3.0, "c");  // drops a
    EXPECT_EQ(p.dropped(), 1u);
    EXPECT_EQ(p.waiting(), 2u);
    p.add_pose(0.5, 0);
    p.add_pose(0.7, 0);
    p.add_pose(0.9, 0);  // drops 0.5
    EXPECT_TRUE(release(p).empty());
    std::vector<std::string> rest;
    p.release_all([&](double, std::string&& s, std::optional<int>&& pose) {
        EXPECT_FALSE(pose.has_value());
        rest.push_back(s);
    });
    EXPECT_EQ(rest, (std::vector<std::string>{"b", "c"}));
    EXPECT_EQ(p.waiting(), 0u);
}

// Brute-force oracle: with every pose at hand and scans released only once all poses came, each
// scan pairs with the pose of its stamp exactly when one exists.
TEST(StampPairerTest, RandomStampsMatchTheOracle) {
    std::srand(7);
    Pairer p(StampPairerOptions{1e-4, 1000, 0, 200});
    std::vector<double> scans, poses;
    for (int i = 0; i < 200; ++i) {
        const double t = i * 0.1;
        scans.push_back(t);
        if (std::rand() % 4 != 0) poses.push_back(t);
    }
    std::vector<Out> out;
    std::size_t pi = 0;
    for (double t : scans) {
        p.add_scan(t, std::to_string(t));
        while (pi < poses.size() && poses[pi] <= t + 0.05) {
            p.add_pose(poses[pi], int(pi));
            ++pi;
        }
        p.release([&](double s, std::string&& scan, std::optional<int>&& pose) {
            out.push_back({s, scan, pose});
        });
    }
    p.release_all([&](double s, std::string&& scan, std::optional<int>&& pose) {
        out.push_back({s, scan, pose});
    });
    ASSERT_EQ(out.size(), scans.size());
    for (std::size_t i = 0; i < out.size(); ++i) {
        EXPECT_DOUBLE_EQ(out[i].stamp, scans[i]);
        bool has = false;
        for (double q : poses) has |= std::abs(q - scans[i]) < 1e-4;
        EXPECT_EQ(out[i].pose.has_value(), has) << "scan " << i;
    }
}

}  // namespace
}  // namespace ltm::runtime
