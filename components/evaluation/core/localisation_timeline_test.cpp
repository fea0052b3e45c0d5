#include "evaluation/core/localisation_timeline.hpp"

#include <gtest/gtest.h>

#include "common/core/cdr_cursor.hpp"

namespace ltm::eval {
namespace {

// A LocalisationStatus as Cyclone writes it (XCDR1, little endian).
std::vector<std::uint8_t> status_cdr(double stamp, std::uint8_t state, bool valid, float confidence,
                                     bool global_ran, double global_time, std::uint32_t relocs,
                                     const std::string& message) {
    std::vector<std::uint8_t> out = {0, 1, 0, 0};
    common::CdrWriter w(out);
    w.write(static_cast<std::int32_t>(stamp));
    w.write(static_cast<std::uint32_t>((stamp - static_cast<std::int32_t>(stamp)) * 1e9));
    const std::string frame = "map";
    w.write(static_cast<std::uint32_t>(frame.size() + 1));
    w.bytes(frame.c_str(), frame.size() + 1);
    w.write(state);
    w.write(static_cast<std::uint8_t>(valid));
    w.write(confidence);
    w.write(0.9f);  // inlier fraction
    w.write(0.0);   // lost_for
    w.write(1.5);   // since_fix
    w.write(static_cast<std::uint8_t>(global_ran));
    w.write(global_time);
    w.write(relocs);
    w.write(static_cast<std::uint32_t>(7));  // skipped scans
    w.write(static_cast<std::uint32_t>(message.size() + 1));
    w.bytes(message.c_str(), message.size() + 1);
    return out;
}

TEST(LocalisationTimeline, DecodesWhatCycloneWrites) {
    const auto cdr = status_cdr(12.25, 3, true, 0.85f, true, 0.17, 2, "relocalised: place 1 of 4");
    StatusSample s;
    std::string error;
    ASSERT_TRUE(decode_localisation_status(cdr.data(), cdr.size(), &s, &error)) << error;
    EXPECT_NEAR(s.stamp, 12.25, 1e-6);
    EXPECT_EQ(s.state, 3);
    EXPECT_TRUE(s.pose_valid);
    EXPECT_FLOAT_EQ(s.confidence, 0.85f);
    EXPECT_TRUE(s.global_ran);
    EXPECT_DOUBLE_EQ(s.global_time, 0.17);
    EXPECT_EQ(s.relocalisations, 2u);
    EXPECT_EQ(s.skipped_scans, 7u);
    EXPECT_EQ(s.message, "relocalised: place 1 of 4");
}

TEST(LocalisationTimeline, RefusesCutAndForeignBytes) {
    auto cdr = status_cdr(1.0, 1, true, 1.0f, false, 0.0, 0, "tracking");
    StatusSample s;
    std::string error;
    for (std::size_t cut : {std::size_t{0}, std::size_t{3}, std::size_t{20}, cdr.size() - 3}) {
        EXPECT_FALSE(decode_localisation_status(cdr.data(), cut, &s, &error)) << cut;
        EXPECT_FALSE(error.empty());
    }
    cdr[1] = 0;  // big-endian CDR: not what ltm writes
    EXPECT_FALSE(decode_localisation_status(cdr.data(), cdr.size(), &s, &error));
}

TEST(LocalisationTimeline, SumsUpStatesEventsAndQueries) {
    std::vector<StatusSample> samples;
    const std::uint8_t states[] = {0, 2, 2, 3, 1, 1, 2, 3, 1, 4};
    for (int i = 0; i < 10; ++i) {
        StatusSample s;
        s.stamp = 100.0 + 0.1 * i;
        s.state = states[i];
        s.pose_valid = states[i] == 1 || states[i] == 3 || states[i] == 4;
        s.global_ran = states[i] == 2 || states[i] == 3;
        s.global_time = 0.1 * (i + 1);
        s.skipped_scans = i / 3;
        samples.push_back(s);
    }
    const TimelineSummary t = summarise_timeline(samples);
    EXPECT_EQ(t.samples, 10u);
    EXPECT_NEAR(t.end - t.start, 0.9, 1e-9);
    EXPECT_EQ(t.in_state[1], 3u);
    EXPECT_EQ(t.in_state[2], 3u);
    EXPECT_EQ(t.valid, 6u);
    EXPECT_EQ(t.relocalisations.size(), 2u);
    EXPECT_EQ(t.losses.size(), 2u);  // two runs of LOST
    EXPECT_EQ(t.global_queries, 5u);
    EXPECT_NEAR(t.global_median, 0.4, 1e-9);  // of 0.2 0.3 0.4 0.7 0.8
    EXPECT_NEAR(t.global_max, 0.8, 1e-9);
    EXPECT_EQ(t.skipped_scans, 3u);
    const std::string svg = timeline_svg(samples, "state");
    EXPECT_NE(svg.find("<svg"), std::string::npos);
    EXPECT_NE(svg.find("tracking"), std::string::npos);
    EXPECT_EQ(summarise_timeline({}).samples, 0u);
}

}  // namespace
}  // namespace ltm::eval
