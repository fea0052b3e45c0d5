#include "evaluation/core/site_objects.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "common/core/io_error.hpp"

namespace ltm::eval {
namespace {

std::string write_tmp(const std::string& name, const std::string& text) {
    const auto path = std::filesystem::temp_directory_path() / name;
    std::ofstream(path) << text;
    return path.string();
}

SiteObject car(std::uint32_t id, double x, double y, double yaw) {
    SiteObject o;
    o.id = id;
    o.kind = "car";
    o.x = x, o.y = y, o.yaw_deg = yaw;
    o.length = 4.5, o.width = 1.8, o.height = 1.5;
    return o;
}

TEST(SiteObjects, ReadsSimulatorObjectsFile) {
    const auto path = write_tmp("ltm_site_objects_test.txt",
                                "# id kind x y base_z yaw_deg length width height changed\n"
                                "172 car -24.350 96.300 -0.146 90.00 4.50 1.80 1.50 1\n\n"
                                "5 fence 10 0 0.1 0 18 0.1 2.2 0\n");
    const auto objects = read_site_objects(path);
    ASSERT_EQ(objects.size(), 2u);
    EXPECT_EQ(objects[0].id, 172u);
    EXPECT_EQ(objects[0].kind, "car");
    EXPECT_DOUBLE_EQ(objects[0].yaw_deg, 90.0);
    EXPECT_TRUE(objects[0].changed);
    EXPECT_FALSE(objects[1].changed);
}

TEST(SiteObjects, BadLineNamesFileAndLine) {
    const auto path = write_tmp("ltm_site_objects_bad.txt", "1 car 0 0 0 0 4 2\n");
    try {
        read_site_objects(path);
        FAIL() << "accepted a short line";
    } catch (const common::IoError& e) {
        EXPECT_NE(std::string(e.what()).find("line 1"), std::string::npos) << e.what();
    }
    EXPECT_THROW(read_site_objects("/nonexistent/objects.txt"), common::IoError);
}

TEST(SiteObjects, ReadsTheGroundUnderAnObjectAndInterpolatesItAlongItsAxis) {
    const auto path = write_tmp("ltm_site_objects_ground.txt",
                                "1 fence 10 5 -0.3 90 16 0.1 2.4 1 -0.3 0.1 0.5\n"
                                "2 car 0 0 0.2 0 4.5 1.8 1.5 0\n");
    const auto objects = read_site_objects(path);
    ASSERT_EQ(objects.size(), 2u);
    ASSERT_EQ(objects[0].ground_z.size(), 3u);
    const SiteObject& f = objects[0];  // along +y: from y = -3 to y = 13
    EXPECT_NEAR(f.ground_at({10, -3, 0}), -0.3, 1e-9);
    EXPECT_NEAR(f.ground_at({10, 1, 0}), -0.1, 1e-9);
    EXPECT_NEAR(f.ground_at({10.05, 9, 0}), 0.3, 1e-9);
    EXPECT_NEAR(f.ground_at({10, 20, 0}), 0.5, 1e-9);  // beyond its end: the end's
    EXPECT_TRUE(objects[1].ground_z.empty());
    EXPECT_DOUBLE_EQ(objects[1].ground_at({1, 0, 0}), 0.2);  // without: base_z
    for (const char* bad :
         {"1 fence 10 5 -0.3 90 16 0.1 2.4 1 -0.3\n",  // one height
          "1 fence 10 5 -0.3 90 16 0.1 2.4 1 -0.3 x\n", "1 car 0 0 0 0 4 2 1 0 nan 0\n"}) {
        EXPECT_THROW(read_site_objects(write_tmp("ltm_site_objects_ground_bad.txt", bad)),
                     common::IoError)
            << bad;
    }
}

TEST(SiteObjects, OrientedBoxContainment) {
    const SiteObject o = car(1, 10, 20, 90);  // 4.5 m along y, 1.8 m along x
    EXPECT_TRUE(o.contains({10, 22, 1}, 0.0));
    EXPECT_FALSE(o.contains({12, 20, 1}, 0.0));
    EXPECT_TRUE(o.contains({10.95, 20, 1}, 0.1));
    EXPECT_FALSE(o.contains({10, 20, 1.7}, 0.1));
    EXPECT_FALSE(o.contains({10, 20, -0.2}, 0.1));
}

TEST(SiteObjects, DiffFindsRemovedMovedAdded) {
    const std::vector<SiteObject> first{car(1, 0, 0, 0), car(2, 10, 0, 0), car(3, 20, 0, 0)};
    const std::vector<SiteObject> later{car(2, 10, 0, 0), car(3, 25, 3, 0), car(9, 40, 0, 0)};
    const ObjectChanges c = diff_objects(first, later);
    ASSERT_EQ(c.removed.size(), 1u);
    EXPECT_EQ(c.removed[0].id, 1u);
    ASSERT_EQ(c.moved_from.size(), 1u);
    EXPECT_DOUBLE_EQ(c.moved_from[0].x, 20.0);
    EXPECT_DOUBLE_EQ(c.moved_to[0].x, 25.0);
    ASSERT_EQ(c.added.size(), 1u);
    EXPECT_EQ(c.added[0].id, 9u);
}

}  // namespace
}  // namespace ltm::eval
