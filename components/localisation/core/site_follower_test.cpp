// The localisation's view of a site whose versions arrive while it runs: only newer intact
// versions are offered, the newest first; a damaged one is said once and passed over.
#include "localisation/core/site_follower.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "map/core/map_store.hpp"
#include "map/core/site_test_maps.hpp"

namespace ltm::localisation {
namespace {

namespace fs = std::filesystem;

// One session committed into the site (a tiny map of `local_maps` local maps).
void commit(map::SiteStore& site, std::size_t local_maps) {
    map::save_map(site.staging_map_dir(), map::test::tiny_map(local_maps, 200));
    site.commit(map::measure_version(site.staging_map_dir(), "", ""), 10);
}

struct TempSite {
    fs::path dir = fs::temp_directory_path() / ("ltm_site_follower_" + std::to_string(::getpid()));
    TempSite() { fs::remove_all(dir); }
    ~TempSite() { fs::remove_all(dir); }
};

TEST(SiteFollower, OffersOnlyNewerIntactVersionsNewestFirst) {
    TempSite t;
    map::SiteStore site(t.dir.string());
    SiteFollower follower(t.dir.string(), 0);
    EXPECT_FALSE(follower.newer()) << "a site with no version (the folder not even made)";
    commit(site, 2);
    auto v = follower.newer();
    ASSERT_TRUE(v);
    EXPECT_EQ(v->name, "v0001");
    follower.adopt(v->number);
    EXPECT_FALSE(follower.newer()) << "nothing newer than the version in use";
    commit(site, 3);
    commit(site, 4);
    v = follower.newer();
    ASSERT_TRUE(v);
    EXPECT_EQ(v->name, "v0003") << "the newest, not the next";
    EXPECT_TRUE(v->intact);
    follower.adopt(v->number);
    EXPECT_FALSE(follower.newer());
}

TEST(SiteFollower, ADamagedNewerVersionIsSaidOnceAndPassedOver) {
    TempSite t;
    map::SiteStore site(t.dir.string());
    commit(site, 2);
    commit(site, 3);
    // v0002's graph cut short on the disk.
    fs::path graph;
    for (const auto& e : fs::directory_iterator(t.dir / "versions/v0002/map"))
        if (e.path().filename().string().rfind("graph_", 0) == 0) graph = e.path();
    ASSERT_FALSE(graph.empty()) << "the map's graph file";
    fs::resize_file(graph, fs::file_size(graph) / 2);
    SiteFollower follower(t.dir.string(), 1);
    std::vector<std::string> notes;
    EXPECT_FALSE(follower.newer(&notes));
    ASSERT_EQ(notes.size(), 1u);
    EXPECT_EQ(notes[0].rfind("v0002 is damaged (", 0), 0u) << notes[0];
    notes.clear();
    EXPECT_FALSE(follower.newer(&notes));
    EXPECT_TRUE(notes.empty()) << "said once";
    commit(site, 4);  // v0003, whole: taken over the damaged one
    const auto v = follower.newer(&notes);
    ASSERT_TRUE(v);
    EXPECT_EQ(v->name, "v0003");
}

}  // namespace
}  // namespace ltm::localisation
