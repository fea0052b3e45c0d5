#include "common/core/point_layout.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

using namespace ltm::common;

namespace {

PointCloud sample_cloud(bool with_time) {
    PointCloud c;
    for (int i = 0; i < 5; ++i) {
        c.points.emplace_back(1.0f * i, -2.0f * i, 0.5f);
        c.intensity.push_back(10.0f * i);
        if (with_time) c.time.push_back(0.01f * i);
    }
    return c;
}

}  // namespace

TEST(PointLayout, RoundTripStandardLayout) {
    for (bool with_time : {false, true}) {
        const PointCloud in = sample_cloud(with_time);
        const PointLayout layout = standard_layout(with_time);
        std::vector<std::uint8_t> data;
        encode_points(in, layout, data);
        ASSERT_EQ(data.size(), in.size() * layout.point_step);
        PointCloud out;
        ASSERT_EQ(decode_points(layout, data.data(), in.size(), 5.0, out), "");
        ASSERT_EQ(out.size(), in.size());
        EXPECT_EQ(out.has_time(), with_time);
        for (std::size_t i = 0; i < in.size(); ++i) {
            EXPECT_EQ(out.points[i], in.points[i]);
            EXPECT_EQ(out.intensity[i], in.intensity[i]);
            if (with_time) {
                EXPECT_FLOAT_EQ(out.time[i], in.time[i]);
            }
        }
    }
}

TEST(PointLayout, OusterStyleLayoutWithPaddingAndNanosecondTime) {
    // x y z at 0/4/8, 4 bytes padding, intensity float at 16, uint32 t (ns) at 20, step 48.
    PointLayout layout;
    layout.point_step = 48;
    layout.fields = {
        {"x", 0, 7, 1}, {"y", 4, 7, 1}, {"z", 8, 7, 1}, {"intensity", 16, 7, 1}, {"t", 20, 6, 1}};
    std::vector<std::uint8_t> data(2 * 48, 0xAB);
    const float p0[3] = {1, 2, 3}, p1[3] = {4, 5, 6};
    const float i0 = 7, i1 = 8;
    const std::uint32_t t0 = 0, t1 = 50'000'000;  // 50 ms
    std::memcpy(&data[0], p0, 12);
    std::memcpy(&data[16], &i0, 4);
    std::memcpy(&data[20], &t0, 4);
    std::memcpy(&data[48], p1, 12);
    std::memcpy(&data[64], &i1, 4);
    std::memcpy(&data[68], &t1, 4);
    PointCloud out;
    ASSERT_EQ(decode_points(layout, data.data(), 2, 0.0, out), "");
    EXPECT_EQ(out.points[1], Eigen::Vector3f(4, 5, 6));
    EXPECT_EQ(out.intensity[1], 8.0f);
    EXPECT_NEAR(out.time[1], 0.05f, 1e-7);
}

TEST(PointLayout, AbsoluteTimestampsBecomeRelative) {
    PointLayout layout;
    layout.point_step = 24;
    layout.fields = {{"x", 0, 7, 1}, {"y", 4, 7, 1}, {"z", 8, 7, 1}, {"timestamp", 16, 8, 1}};
    std::vector<std::uint8_t> data(24, 0);
    const double stamp = 1.7e9, t = 1.7e9 + 0.025;
    std::memcpy(&data[16], &t, 8);
    PointCloud out;
    ASSERT_EQ(decode_points(layout, data.data(), 1, stamp, out), "");
    EXPECT_NEAR(out.time[0], 0.025, 1e-6);
}

TEST(PointLayout, RejectsUnsupportedLayoutsWithReason) {
    PointLayout doubles;
    doubles.point_step = 24;
    doubles.fields = {{"x", 0, 8, 1}, {"y", 8, 8, 1}, {"z", 16, 8, 1}};
    std::vector<std::uint8_t> data(24, 0);
    PointCloud out;
    EXPECT_NE(decode_points(doubles, data.data(), 1, 0, out).find("need float32"),
              std::string::npos);

    PointLayout no_z;
    no_z.point_step = 8;
    no_z.fields = {{"x", 0, 7, 1}, {"y", 4, 7, 1}};
    EXPECT_NE(decode_points(no_z, data.data(), 1, 0, out).find("no 'z' field"), std::string::npos);

    PointLayout overflow;
    overflow.point_step = 8;
    overflow.fields = {{"x", 0, 7, 1}, {"y", 4, 7, 1}, {"z", 8, 7, 1}};
    EXPECT_NE(decode_points(overflow, data.data(), 1, 0, out).find("does not fit"),
              std::string::npos);

    PointLayout big = standard_layout(false);
    big.big_endian = true;
    EXPECT_NE(decode_points(big, data.data(), 1, 0, out).find("big-endian"), std::string::npos);
}

TEST(PointCloud, RemoveNonFiniteKeepsChannelsAligned) {
    PointCloud c = sample_cloud(true);
    c.points[1].x() = std::numeric_limits<float>::quiet_NaN();
    c.points[3].z() = std::numeric_limits<float>::infinity();
    EXPECT_EQ(remove_non_finite(c), 2u);
    ASSERT_EQ(c.size(), 3u);
    EXPECT_TRUE(c.consistent());
    EXPECT_EQ(c.intensity[1], 20.0f);
    EXPECT_FLOAT_EQ(c.time[2], 0.04f);
}
