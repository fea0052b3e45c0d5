#include "mapping/component/place_descriptor_msg.hpp"

#include <gtest/gtest.h>

#include "registration/core/test_data.hpp"
#include "runtime/convert/local_map.hpp"
#include "runtime/testing/dds_loopback.hpp"

namespace ltm::mapping {
namespace {

// A digested keyframe through Cyclone DDS: its two descriptors, its segment and its points come
// back as they went.
TEST(PlaceDescriptorMsg, ADigestedKeyframeCrossesDdsUnchanged) {
    MapperConfig config;
    KeyframeDigester digester(config);
    common::KeyframeData k;
    k.id = 7;
    k.local_map_id = 3;
    k.segment = 2;
    k.stamp = 12.5;
    const std::vector<Eigen::Vector3f> whole = registration::test::view(
        registration::test::synthetic_scene(5), Eigen::Isometry3d::Identity(), 50.0);
    KeyframeDescriptors d;
    digester.digest(whole, &d, &k.points);
    convert::KeyframeBuilder builder;
    msg::Keyframe m = builder.build(k, "odom", "lidar");
    borrow_into(d.loop, &m.descriptor);
    borrow_into(d.localisation, &m.localisation_descriptor);
    runtime::testing::DdsLoopback dds(232);
    bool taken = false;
    dds.roundtrip<msg::Keyframe>(m, [&](const msg::Keyframe& back) {
        taken = true;
        const common::KeyframeData kb = convert::from_msg(back);
        EXPECT_EQ(kb.segment, std::optional<std::uint32_t>(2));
        EXPECT_EQ(kb.points, k.points);
        std::string problem;
        const MadeDescriptor loop = from_msg(back.descriptor, &problem);
        EXPECT_EQ(problem, "");
        EXPECT_TRUE(usable(loop, config.scan_context));
        EXPECT_EQ(loop.descriptor.value, d.loop.descriptor.value);
        EXPECT_EQ(loop.descriptor.occupied, d.loop.descriptor.occupied);
        const MadeDescriptor loc = from_msg(back.localisation_descriptor, &problem);
        EXPECT_TRUE(usable(loc, config.localisation_descriptor));
        EXPECT_EQ(loc.descriptor.value, d.localisation.descriptor.value);
        EXPECT_EQ(loc.descriptor.spread, d.localisation.descriptor.spread);
    });
    EXPECT_TRUE(taken);
}

TEST(PlaceDescriptorMsg, NoneOrADamagedOneIsEmptyWithAReason) {
    msg::PlaceDescriptor none{};
    std::string problem = "x";
    EXPECT_TRUE(from_msg(none, &problem).descriptor.empty());
    EXPECT_EQ(problem, "");  // none is not a problem
    const MadeDescriptor made{
        places::make_scan_context(registration::test::view(registration::test::synthetic_scene(6),
                                                           Eigen::Isometry3d::Identity(), 50.0),
                                  places::ScanContextConfig()),
        places::ScanContextConfig()};
    msg::PlaceDescriptor m;
    borrow_into(made, &m);
    EXPECT_FALSE(from_msg(m, &problem).descriptor.empty());
    m.values._length -= 1;  // arrays shorter than rings x sectors
    EXPECT_TRUE(from_msg(m, &problem).descriptor.empty());
    EXPECT_NE(problem.find("20 x 60"), std::string::npos) << problem;
    borrow_into(made, &m);
    m.kind = 7;
    EXPECT_TRUE(from_msg(m, &problem).descriptor.empty());
    EXPECT_NE(problem.find("kind 7"), std::string::npos) << problem;
}

}  // namespace
}  // namespace ltm::mapping
