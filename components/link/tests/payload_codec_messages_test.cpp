// The payload codec on the bytes Cyclone DDS itself serialises for ltm's keyframes and local maps:
// its layout-aware codecs apply (a change to Keyframe.idl or LocalMap.idl that they no longer
// follow shows here, not as a silent fall-back to plain zstd) and every byte comes back.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "link/core/payload_codec.hpp"
#include "runtime/convert/local_map.hpp"
#include "runtime/messages.hpp"
#include "runtime/testing/dds_loopback.hpp"

using namespace ltm;

namespace {

// A loopback-only domain no other test of the binary uses.
runtime::testing::DdsLoopback& dds() {
    static runtime::testing::DdsLoopback d(227);
    return d;
}

common::LocalMapData local_map(int voxels) {
    std::mt19937 rng(3);
    std::uniform_int_distribution<int> cell(-60, 60), seen(0, 4);
    std::uniform_real_distribution<float> unit(0, 1);
    common::LocalMapData m;
    m.id = 12;
    m.revision = 3;
    m.finished = true;
    m.voxel_size = 0.6f;
    m.observation_times = {50.0, 50.1, 50.2, 50.3};
    for (int i = 0; i < voxels; ++i) {
        common::VoxelData v;
        v.index = {cell(rng), cell(rng), cell(rng) / 8};
        v.centre = (v.index.cast<float>() + Eigen::Vector3f(unit(rng), unit(rng), unit(rng))) *
                   m.voxel_size;
        v.normal = Eigen::Vector3f(unit(rng), unit(rng), 1.0f).normalized();
        v.point_count = 1 + static_cast<std::uint32_t>(40 * unit(rng));
        v.planarity = unit(rng);
        v.stability = unit(rng);
        v.life.created = 50.0;
        v.life.last_seen = m.observation_times[i % 4];
        v.life.observations = 4;
        for (int s = seen(rng); s > 0; --s) v.life.seen.push_back(static_cast<std::uint16_t>(s));
        m.voxels.push_back(v);
    }
    return m;
}

}  // namespace

TEST(PayloadCodecMessages, CycloneSerialisedLocalMapsGoAsColumns) {
    const common::LocalMapData map = local_map(2000);
    convert::LocalMapBuilder builder;
    const std::vector<std::uint8_t> cdr = dds().serialize(builder.build(map, 50.3, "odom"));
    ASSERT_GT(cdr.size(), 2000u * 76u);
    EXPECT_NE(cdr[3], 0);  // Cyclone's padding count: `seen` left the size off a multiple of 4
    const std::string type = "ltm_msgs::msg::dds_::LocalMap_";
    const std::vector<std::uint8_t> wire = link::encode_payload(type, cdr);
    EXPECT_EQ(link::payload_codec(wire), link::PayloadCodec::kLocalMap);
    EXPECT_EQ(link::decode_payload(type, wire), cdr);
    EXPECT_LT(wire.size(), cdr.size() / 2);
}

TEST(PayloadCodecMessages, CycloneSerialisedKeyframesAreShuffled) {
    std::mt19937 rng(4);
    std::uniform_real_distribution<float> coordinate(-40, 40);
    common::KeyframeData k;
    k.id = 5;
    k.scan_index = 50;
    k.local_map_id = 1;
    k.stamp = 5.0;
    for (int i = 0; i < 5000; ++i)
        k.points.emplace_back(coordinate(rng), coordinate(rng), coordinate(rng) / 10);
    convert::KeyframeBuilder builder;
    const std::vector<std::uint8_t> cdr = dds().serialize(builder.build(k, "odom", "lidar"));
    ASSERT_GT(cdr.size(), 5000u * 12u);
    const std::string type = "ltm_msgs::msg::dds_::Keyframe_";
    const std::vector<std::uint8_t> wire = link::encode_payload(type, cdr);
    EXPECT_EQ(link::payload_codec(wire), link::PayloadCodec::kShuffled);
    EXPECT_EQ(link::decode_payload(type, wire), cdr);
}
