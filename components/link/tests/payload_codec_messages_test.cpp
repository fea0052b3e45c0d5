// The payload codec on the bytes Cyclone DDS itself serialises for ltm's keyframes and local maps:
// its layout-aware codecs apply (a change to Keyframe.idl or LocalMap.idl that they no longer
// follow shows here, not as a silent fall-back to plain zstd) and every byte comes back.
#include <dds/dds.h>
#include <dds/ddsi/ddsi_serdata.h>
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "common/convert/local_map.hpp"
#include "link/core/payload_codec.hpp"
#include "runtime/messages.hpp"

using namespace ltm;

namespace {

// One participant for the test binary, on a loopback-only domain no other test uses.
dds_entity_t participant() {
    static const dds_domainid_t id = 227;
    static const dds_entity_t domain = dds_create_domain(
        id,
        "<CycloneDDS><Domain Id=\"any\"><General><Interfaces><NetworkInterface name=\"lo\"/>"
        "</Interfaces><AllowMulticast>false</AllowMulticast></General></Domain></CycloneDDS>");
    static const dds_entity_t p =
        domain > 0 ? dds_create_participant(id, nullptr, nullptr) : domain;
    return p;
}

// The serialized CDR (with its encapsulation header) of `sample`, as Cyclone puts it on the wire:
// written and taken back as CDR in one participant.
template <class T>
std::vector<std::uint8_t> serialize(const T& sample) {
    const dds_entity_t participant = ::participant();
    static int topics = 0;
    std::vector<std::uint8_t> out;
    EXPECT_GT(participant, 0) << dds_strretcode(participant);
    const std::string name = "rt/ltm_test/payload_codec_" + std::to_string(topics++);
    const dds_entity_t topic = dds_create_topic(
        participant, runtime::MessageTraits<T>::descriptor(), name.c_str(), nullptr, nullptr);
    dds_qos_t* qos = dds_create_qos();
    dds_qset_reliability(qos, DDS_RELIABILITY_RELIABLE, DDS_SECS(1));
    const dds_entity_t reader = dds_create_reader(participant, topic, qos, nullptr);
    const dds_entity_t writer = dds_create_writer(participant, topic, qos, nullptr);
    dds_delete_qos(qos);
    EXPECT_EQ(dds_write(writer, &sample), DDS_RETCODE_OK);
    struct ddsi_serdata* sd = nullptr;
    dds_sample_info_t info;
    if (dds_takecdr(reader, &sd, 1, &info, DDS_ANY_STATE) == 1) {
        out.resize(ddsi_serdata_size(sd));
        ddsi_serdata_to_ser(sd, 0, out.size(), out.data());
        ddsi_serdata_unref(sd);
    }
    dds_delete(writer);
    dds_delete(reader);
    dds_delete(topic);
    return out;
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
    const std::vector<std::uint8_t> cdr = serialize(builder.build(map, 50.3, "odom"));
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
    const std::vector<std::uint8_t> cdr = serialize(builder.build(k, "odom", "lidar"));
    ASSERT_GT(cdr.size(), 5000u * 12u);
    const std::string type = "ltm_msgs::msg::dds_::Keyframe_";
    const std::vector<std::uint8_t> wire = link::encode_payload(type, cdr);
    EXPECT_EQ(link::payload_codec(wire), link::PayloadCodec::kShuffled);
    EXPECT_EQ(link::decode_payload(type, wire), cdr);
}
