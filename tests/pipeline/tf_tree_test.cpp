// The transform tree through the host (issue 29 item 2): robot_lifelong.yaml on tiny_loop, the
// day recorded. /tf_static holds base_link -> lidar (the launch config's extrinsic, here a given
// one); every /tf message's chain map -> odom -> base_link -> lidar is the localisation's
// published map pose of that scan.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <map>

#include "common/core/cdr_cursor.hpp"
#include "common/core/trajectory_io.hpp"
#include "host/launch_paths.hpp"
#include "host/process.hpp"
#include "host/stamped_poses.hpp"
#include "host/temp_dir_test.hpp"
#include "recorder/core/mcap_reader.hpp"

namespace fs = std::filesystem;
using ltm::tests::kHost;
using ltm::tests::Process;
using namespace ltm;

namespace {

const std::string kConfig = std::string(LTM_SOURCE_DIR) + "/launch_configs/robot_lifelong.yaml";
const std::string kScenario = ltm::tests::scenario("tiny_loop.yaml");

struct Tf {
    long long stamp_ms = 0;
    std::string parent, child;
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
};

// A TFMessage's transforms, from its CDR (XCDR1, little endian).
std::vector<Tf> decode_tf(const std::uint8_t* data, std::size_t size) {
    common::CdrReader r(data, size);
    std::uint32_t n = 0;
    std::vector<Tf> out;
    if (!r.read(n)) return out;
    for (std::uint32_t i = 0; i < n; ++i) {
        std::int32_t sec = 0;
        std::uint32_t nsec = 0;
        double v[7];
        Tf t;
        if (!(r.read(sec) && r.read(nsec) && r.read_string(t.parent) && r.read_string(t.child)))
            return {};
        for (double& x : v)
            if (!r.read(x)) return {};
        t.stamp_ms = std::llround((sec + nsec * 1e-9) * 1000.0);
        t.T.translation() = Eigen::Vector3d(v[0], v[1], v[2]);
        t.T.linear() = Eigen::Quaterniond(v[6], v[3], v[4], v[5]).normalized().toRotationMatrix();
        out.push_back(t);
    }
    return out;
}

class TfTree : public ltm::tests::TempDirTest {
  protected:
    TfTree() : TempDirTest("ltm_tf_tree_") {}
};

TEST_F(TfTree, TheChainIsTheMapPoseOfEveryScan) {
    const std::string out = path("day0");
    setenv("LTM_SITE", path("site").c_str(), 1);
    setenv("LTM_SCENARIO", kScenario.c_str(), 1);
    setenv("LTM_OUT", out.c_str(), 1);
    Process host({kHost, kConfig, "--set", "domain_id=232", "--set",
                  "dds={interfaces: [lo], multicast: false, peers: [127.0.0.1]}", "--set",
                  "odometry.preset=vlp16", "--set", "localisation.preset=vlp16", "--set",
                  "mapping.preset=vlp16", "--set", "tf.base_to_lidar=[0.2, 0, 1.5, 0, 0, 90]"},
                 out + "_host");
    ASSERT_EQ(host.wait(600), 0) << host.err();

    const std::map<long long, Eigen::Isometry3d> map_poses =
        tests::poses_by_stamp_ms(out + "/localisation_tum.txt");
    ASSERT_GE(map_poses.size(), 20u);

    recorder::McapReader reader(out + "/lifelong.mcap");
    recorder::ReadOptions only;
    only.topics = {"rt/tf_static"};
    auto statics = reader.messages(only);
    recorder::MessageView m;
    ASSERT_TRUE(statics.next(m)) << "nothing on /tf_static";
    const std::vector<Tf> s = decode_tf(m.data, m.size);
    ASSERT_EQ(s.size(), 1u);
    EXPECT_EQ(s[0].parent, "base_link");
    EXPECT_EQ(s[0].child, "lidar");
    EXPECT_TRUE(s[0].T.translation().isApprox(Eigen::Vector3d(0.2, 0.0, 1.5), 1e-9));
    EXPECT_TRUE(
        (s[0].T.linear() * Eigen::Vector3d::UnitX()).isApprox(Eigen::Vector3d::UnitY(), 1e-9));

    only.topics = {"rt/tf"};
    auto tf = reader.messages(only);
    std::size_t chains = 0, odom_only = 0;
    for (; tf.next(m);) {
        const std::vector<Tf> t = decode_tf(m.data, m.size);
        ASSERT_FALSE(t.empty()) << "an undecodable TFMessage";
        if (t.size() == 1 && t[0].parent == "map") continue;  // a correction alone
        if (t.size() == 1) {
            EXPECT_EQ(t[0].parent, "odom");
            ++odom_only;
            continue;
        }
        ASSERT_EQ(t.size(), 2u);
        EXPECT_EQ(t[0].parent, "map");
        EXPECT_EQ(t[0].child, "odom");
        EXPECT_EQ(t[1].parent, "odom");
        EXPECT_EQ(t[1].child, "base_link");
        const auto pose = map_poses.find(t[1].stamp_ms);
        if (pose == map_poses.end()) continue;
        const Eigen::Isometry3d T_map_lidar = t[0].T * t[1].T * s[0].T;
        EXPECT_LT((T_map_lidar.translation() - pose->second.translation()).norm(), 0.05)
            << "scan at " << t[1].stamp_ms << " ms";
        ++chains;
    }
    EXPECT_GE(chains, map_poses.size() * 8 / 10) << odom_only << " without map -> odom";
}

}  // namespace
