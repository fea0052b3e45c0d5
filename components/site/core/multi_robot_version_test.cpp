// Several robots changing one site on one day end in one version (issue 26): the base station's
// mapping keeps one graph of both robots' sessions and saves it into the site's staging; the
// commit makes one version whose summary names both sessions and their robots, and a robot that
// holds the previous version fetches only what the two sessions changed.
#include <gtest/gtest.h>

#include "common/core/file_io.hpp"
#include "map/core/version_summary.hpp"
#include "site/core/sync_test_sites.hpp"
#include "site/core/transfer_plan.hpp"

namespace ltm::site_sync {
namespace {

namespace fs = std::filesystem;

// `map` with localisation descriptors (format 3: sessions recorded), node n of session `of(n)`.
map::MapData with_sessions(map::MapData map, std::vector<map::SessionRecord> sessions,
                           const std::vector<std::uint32_t>& node_session) {
    map.localisation_descriptor_config = map.descriptor_config;
    for (std::size_t n = 0; n < map.nodes.size(); ++n) {
        map.nodes[n].session = node_session[n];
        map.local_maps[n].session = node_session[n];
    }
    for (auto& k : map.keyframes) {
        auto copy = std::make_shared<map::StoredKeyframe>(*k);
        copy->session = node_session[copy->node];
        copy->localisation_descriptor = copy->descriptor;
        k = copy;
    }
    map.sessions = std::move(sessions);
    return map;
}

TEST(MultiRobotVersion, TwoRobotsOneDayOneVersion) {
    const fs::path root = fs::path(LTM_BINARY_DIR) / "site_sync_test" / "multi";
    fs::remove_all(root);
    map::SiteStore base((root / "base").string());
    // Day 1: one robot maps 3 local maps.
    test::session(
        base, with_sessions(map::test::tiny_map(3, 500), {{0, 10, 20, 3, 0, ""}}, {0, 0, 0}), 1);
    // Day 2: robot1 and robot2 drive at once; robot1 adds a local map, robot2 another and folds
    // into local map 1 (updated). One mapping, one staging, one commit.
    map::MapData day2 = map::test::tiny_map(5, 500);
    day2.local_maps[1].data = map::test::tiny_local_map(1, 77, 500);
    day2 = with_sessions(
        day2, {{0, 10, 20, 3, 0, ""}, {1, 30, 40, 1, 0, "robot1"}, {2, 31, 41, 1, 1, "robot2"}},
        {0, 0, 0, 1, 2});
    const map::SiteVersion v2 = test::session(base, day2, 2);
    EXPECT_EQ(v2.name, "v0002");
    const auto versions = base.versions();
    ASSERT_EQ(versions.size(), 2u);
    const map::VersionSummary s = map::parse_version_text(
        common::read_file(versions[1].summary_file(), "version.txt"), "version.txt");
    const std::vector<std::pair<std::uint32_t, std::string>> both{{1, "robot1"}, {2, "robot2"}};
    EXPECT_EQ(s.sessions_added, both);
    EXPECT_EQ(s.local_maps_added, 2u);
    EXPECT_EQ(s.local_maps_updated, 1u);
    EXPECT_NE(map::version_line(s).find("sessions 1 (robot1), 2 (robot2)"), std::string::npos)
        << map::version_line(s);
    // A robot holding v0001 fetches the two new local maps, the updated one and the small files.
    const std::string robot = test::robot_site(root, base.dir());
    HeldFiles held;
    held.add_site(robot);
    const VersionOffer offer = scan_version(versions[1].dir, 2, 4096);
    const TransferPlan plan = plan_transfer(offer, held);
    std::size_t local_maps = 0;
    for (std::size_t i = 0; i < offer.files.size(); ++i)
        local_maps += plan.sends(i) && offer.files[i].path.rfind("map/local_maps/", 0) == 0;
    EXPECT_EQ(local_maps, 3u);
}

}  // namespace
}  // namespace ltm::site_sync
