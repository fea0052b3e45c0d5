#include "link/core/robot_ids.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>

#include "common/core/cdr_cursor.hpp"
#include "common/core/io_error.hpp"

namespace ltm::link {
namespace {

namespace fs = std::filesystem;

const std::string kKeyframe = "ltm_msgs::msg::dds_::Keyframe_";
const std::string kLocalMap = "ltm_msgs::msg::dds_::LocalMap_";

// The leading fields of a Keyframe_ / LocalMap_ as Cyclone lays them out (XCDR1 LE), then some
// bytes of the rest.
void header(common::CdrWriter& w) {
    w.write(std::int32_t{100});
    w.write(std::uint32_t{5});
    const char frame[] = "odom";
    w.write(std::uint32_t{sizeof frame});
    w.bytes(frame, sizeof frame);
}
std::vector<std::uint8_t> keyframe(std::uint64_t id, std::uint64_t map, std::uint32_t segment,
                                   std::uint64_t scan_index = 1000) {
    std::vector<std::uint8_t> out{0, 1, 0, 0};
    common::CdrWriter w(out);
    header(w);
    w.write(id);
    w.write(scan_index);  // the scan's index in its input: not renumbered
    w.write(map);
    w.write(segment);
    w.write(1.5);  // pose...
    return out;
}
std::vector<std::uint8_t> local_map(std::uint64_t id, std::uint32_t segment) {
    std::vector<std::uint8_t> out{0, 1, 0, 0};
    common::CdrWriter w(out);
    header(w);
    w.write(id);
    w.write(std::uint32_t{3});  // revision
    w.write(std::uint8_t{1});   // finished
    w.write(segment);
    w.write(2.5);  // anchor...
    return out;
}

class RobotIdsTest : public ::testing::Test {
  protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() / ("ltm_robot_ids_" + std::to_string(::getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
        file_ = (dir_ / "ids").string();
    }
    void TearDown() override { fs::remove_all(dir_); }
    fs::path dir_;
    std::string file_;
};

TEST_F(RobotIdsTest, TheFirstRunGoesOutUnchangedAndARestartContinuesAfterIt) {
    {
        RobotIdRenumbering first(file_);
        EXPECT_EQ(first.offsets(), RobotIds{});
        std::vector<std::uint8_t> k = keyframe(41, 6, 1), m = local_map(6, 1);
        const auto k0 = k, m0 = m;
        EXPECT_TRUE(first.renumber(kKeyframe, k));
        EXPECT_TRUE(first.renumber(kLocalMap, m));
        EXPECT_EQ(k, k0);
        EXPECT_EQ(m, m0);
        EXPECT_EQ(first.next(), (RobotIds{42, 7, 2}));
        first.save();
    }
    RobotIdRenumbering second(file_);  // the robot restarted: its odometry counts from 0 again
    EXPECT_EQ(second.offsets(), (RobotIds{42, 7, 2}));
    std::vector<std::uint8_t> k = keyframe(0, 0, 0), m = local_map(0, 0), other = k;
    EXPECT_TRUE(second.renumber(kKeyframe, k));
    EXPECT_TRUE(second.renumber(kLocalMap, m));
    EXPECT_EQ(k, keyframe(42, 7, 2));  // scan_index and the rest untouched
    EXPECT_EQ(m, local_map(7, 2));
    EXPECT_FALSE(second.renumber("ltm_msgs::msg::dds_::Status_", other));
    EXPECT_EQ(other, keyframe(0, 0, 0));
    second.save();
    EXPECT_EQ(RobotIdRenumbering(file_).offsets(), (RobotIds{43, 8, 3}));
}

TEST_F(RobotIdsTest, AMessageCutShortIsLeftAlone) {
    { std::ofstream(file_) << "ltm robot ids 1\nkeyframe 5\nlocal_map 2\nsegment 1\n"; }
    RobotIdRenumbering ids(file_);
    std::vector<std::uint8_t> k = keyframe(1, 1, 0);
    k.resize(30);  // within local_map_id
    const auto before = k;
    EXPECT_FALSE(ids.renumber(kKeyframe, k));
    EXPECT_EQ(k, before);
    std::vector<std::uint8_t> not_cdr = {9, 9, 9, 9, 1, 2, 3};
    EXPECT_FALSE(ids.renumber(kLocalMap, not_cdr));
    EXPECT_EQ(ids.next(), (RobotIds{5, 2, 1}));
}

TEST_F(RobotIdsTest, ADamagedFileIsOneLineNamingIt) {
    { std::ofstream(file_) << "ltm robot ids 1\nkeyframe x\n"; }
    try {
        RobotIdRenumbering ids(file_);
        FAIL() << "accepted";
    } catch (const common::IoError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find(file_), std::string::npos) << what;
        EXPECT_NE(what.find("damaged"), std::string::npos) << what;
        EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
}

}  // namespace
}  // namespace ltm::link
