// link_applied: the file of what a saved map holds of the link's packets, and how the mapping
// learns it from the downlink's marks (issue 28, item 4).
#include "map/core/link_applied.hpp"

#include <gtest/gtest.h>

#include <filesystem>

#include "common/core/file_io.hpp"
#include "common/core/io_error.hpp"

namespace ltm::map {
namespace {

TEST(LinkApplied, TheFileRoundTripsAndKeepsTheLargerThrough) {
    LinkApplied a;
    a["robot1"][0x0123456789abcdefull] = 41;
    a["robot1"][7] = 3;
    a["robot2"][0xffffffffffffffffull] = 18446744073709551615ull;
    const std::string text = write_link_applied(a, 0xabcdef0123456789ull);
    EXPECT_EQ(text.substr(0, 61),
              "manifest abcdef0123456789\nlink robot1 0000000000000007 3\nlink");
    std::uint64_t hash = 0;
    EXPECT_EQ(parse_link_applied(text, &hash), a);
    EXPECT_EQ(hash, 0xabcdef0123456789ull);
    LinkApplied b;
    b["robot1"][7] = 9;
    b["robot1"][0x0123456789abcdefull] = 40;
    merge_link_applied(a, b);
    EXPECT_EQ(a["robot1"][7], 9u);
    EXPECT_EQ(a["robot1"][0x0123456789abcdefull], 41u);
}

TEST(LinkApplied, AMalformedLineIsOneLineNamingIt) {
    for (const std::string bad : {"link robot1 12 5\n", "link robot1 0000000000000001\n",
                                  "link robot1 0000000000000001 x\n", "kink r 0000000000000001 1\n",
                                  "link r 0000000000000001 1 2\n"}) {
        try {
            parse_link_applied("manifest 0000000000000001\n" + bad, nullptr);
            ADD_FAILURE() << "accepted: " << bad;
        } catch (const common::FormatError& e) {
            EXPECT_NE(std::string(e.what()).find("line 2"), std::string::npos) << e.what();
        }
    }
    EXPECT_THROW(parse_link_applied("link r 0000000000000001 1\n", nullptr), common::FormatError)
        << "the manifest line comes first";
    EXPECT_THROW(parse_link_applied("", nullptr), common::FormatError) << "cut short";
}

TEST(LinkApplied, NoFileOrAnotherSavesRecordIsNothingApplied) {
    const std::string dir = ::testing::TempDir() + "/link_applied_test";
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    EXPECT_TRUE(read_link_applied(dir).empty());
    common::write_file_atomic(dir + "/manifest.txt", std::string("a save's manifest\n"));
    LinkApplied a;
    a["r"][1] = 5;
    save_link_applied(dir, a);
    EXPECT_EQ(read_link_applied(dir), a);
    // Another save's manifest beside it (a snapshot taken while a save replaced the files).
    common::write_file_atomic(dir + "/manifest.txt", std::string("the next save's manifest\n"));
    std::string note;
    EXPECT_TRUE(read_link_applied(dir, &note).empty());
    EXPECT_NE(note.find("another save's manifest"), std::string::npos) << note;
    std::filesystem::remove_all(dir);
}

TEST(DeliveryTracker, AMarkIsAppliedOnlyOnceEveryCountedMessageWasTaken) {
    DeliveryTracker t;
    // The downlink handed on 2 keyframes and a local map (packets 1..3), then a map change (4).
    t.mark("robot1", "robot1", 5, 3, {2, 1, 0});
    t.mark("robot1", "robot1", 5, 4, {2, 1, 1});
    EXPECT_TRUE(t.applied().empty());
    t.took_keyframe("robot1");
    t.took_local_map("robot1");
    EXPECT_TRUE(t.applied().empty()) << "one keyframe still in the mapping's queue";
    t.took_map_changes("robot1");  // another topic's queue ran ahead
    EXPECT_TRUE(t.applied().empty());
    t.took_keyframe("robot1");
    ASSERT_EQ(t.applied().count("robot1"), 1u);
    EXPECT_EQ(t.applied().at("robot1").at(5), 4u) << "both marks reached";
    EXPECT_EQ(t.pending(), 0u);
    // Another robot's messages do not count for this one.
    t.mark("robot2", "robot2", 9, 1, {1, 0, 0});
    t.took_keyframe("robot1");
    EXPECT_EQ(t.applied().count("robot2"), 0u);
    t.took_keyframe("robot2");
    EXPECT_EQ(t.applied().at("robot2").at(9), 1u);
}

TEST(DeliveryTracker, MapChangesDoNotHoldBackAMappingThatDoesNotReadThem) {
    DeliveryTracker t(false);
    t.seed({{"robot", {{3, 10}}}});
    t.mark("", "robot", 4, 2, {1, 0, 1});
    t.took_keyframe("");
    EXPECT_EQ(t.applied().at("robot").at(4), 2u);
    EXPECT_EQ(t.applied().at("robot").at(3), 10u) << "what the loaded map held stays";
}

}  // namespace
}  // namespace ltm::map
