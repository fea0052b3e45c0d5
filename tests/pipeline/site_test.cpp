// The `site` component through the host (issue 26, item 3): a session commits what was staged as
// the site's next version at SIGTERM; nothing staged is NOT saved (exit 4) and the previous
// version stays the newest; a second live session on the site, and a named version that is
// unknown, are refused in one line (exit 2); a staging a crashed session left is removed, and the
// mapping's first save into the staging (before the site component's construction) is kept; the
// localisation on a new site says there is no map yet, takes the site's anchor, and refuses a
// damaged anchor in one line. The map is staged by the test itself
// (the mapping's part is the lead's); the host runs the real site component.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include "host/launch_paths.hpp"
#include "host/process.hpp"
#include "host/temp_dir_test.hpp"
#include "map/core/map_store.hpp"
#include "map/core/site_anchor.hpp"
#include "map/core/site_staging.hpp"
#include "map/core/site_store.hpp"
#include "map/core/site_test_maps.hpp"

namespace fs = std::filesystem;
using ltm::tests::kHost;
using ltm::tests::Process;
using namespace ltm;

namespace {

class SitePipeline : public ltm::tests::TempDirTest {
  protected:
    SitePipeline() : TempDirTest("ltm_site_") {}

    std::string config(int domain, const std::string& site, const std::string& extra = "") {
        return write("site" + std::to_string(domain) + ".yaml",
                     "domain_id: " + std::to_string(domain) +
                         "\ndds: {interfaces: [lo], multicast: false, peers: [127.0.0.1]}\n"
                         "components:\n" +
                         extra + "  - name: site\n    type: site\n    params: {site_dir: " + site +
                         ", keep_versions: 3}\n");
    }

    // A site with one version, made as a session would.
    void make_first_version(const std::string& site) {
        map::SiteStore store(site);
        map::save_map(store.staging_map_dir(), map::test::tiny_map(2));
        map::test::write_maintained_map(store.staging_maintained_map_file(), 1);
        store.commit(map::measure_version(store.staging_map_dir(), "", ""), 3);
    }
};

}  // namespace

TEST_F(SitePipeline, TheStagedSessionBecomesTheNextVersionAndASecondSessionIsRefused) {
    const std::string site = path("site");
    make_first_version(site);
    fs::create_directories(fs::path(site) / "next/map");  // a crashed session's staging
    Process host({kHost, config(171, site)}, path("host"));
    ASSERT_TRUE(host.wait_for_log("the session starts from v0001", 60)) << host.err();
    EXPECT_NE(host.err().find("the staging of a session that did not finish"), std::string::npos)
        << host.err();

    Process second({kHost, config(172, site)}, path("second"));
    EXPECT_EQ(second.wait(60), 2) << second.err();
    EXPECT_NE(second.err().find("the site is in use by pid"), std::string::npos) << second.err();

    // What the mapping and the maintenance of this session would save.
    map::SiteStore store(site);
    map::SaveOptions options;
    options.link_from = store.start_version("")->map_dir();
    map::save_map(store.staging_map_dir(), map::test::tiny_map(3), options);
    map::test::write_maintained_map(store.staging_maintained_map_file(), 2);
    host.signal(SIGTERM);
    ASSERT_EQ(host.wait(60), 0) << host.err();
    EXPECT_NE(host.err().find("saved site version (site): " + site +
                              "/versions/v0002 (v0002: 1 "
                              "local maps added, 0 updated (3); 2 keyframes added"),
              std::string::npos)
        << host.err();
    const auto versions = store.versions();
    ASSERT_EQ(versions.size(), 2u);
    EXPECT_TRUE(versions[1].intact) << versions[1].problem;
    EXPECT_FALSE(fs::exists(store.staging_dir()));
    EXPECT_EQ(map::load_map(versions[1].map_dir()).map.local_maps.size(), 3u);
}

// A composed host as robot_lifelong.yaml: the mapping (constructed before the site component)
// claims the staging and saves into it at its construction; the site component shares the claim
// and keeps that save (before, it removed SITE/next whenever it existed: "the staging of a session
// that did not finish", right after the mapping's first save). A staging an earlier session left
// (marked by it, a dead pid) is still removed, once, before the mapping's first save.
TEST_F(SitePipeline, TheMappingsFirstSaveIsKeptAndAnEarlierSessionsStagingRemoved) {
    const std::string site = path("site");
    make_first_version(site);
    map::SiteStore store(site);
    fs::create_directories(store.staging_map_dir());
    std::ofstream(store.staging_map_dir() + "/lm_earlier.bin") << "an earlier session's file";
    std::ofstream(store.staging_marker_file())
        << "ltm site staging\nsession earlier\npid 999999\nclaimed 2026-11-28 10:00:00 UTC\n";
    const std::string mapping =
        "  - name: mapping\n    type: mapping\n    params: {site_dir: " + site +
        ", save_period_s: 60, cpu_budget: background, scan_context: {rings: 6, sectors: 12, "
        "max_range: 80, min_range: 0, sensor_height: 2}}\n";  // the tiny map's; saves at once
    Process host({kHost, config(177, site, mapping)}, path("host"));
    ASSERT_TRUE(host.wait_for_log("the session starts from v0001", 60)) << host.err();
    const std::string err = host.err();
    const std::string removed = "removed " + site +
                                "/next: the staging of a session that did not finish (pid 999999, "
                                "claimed 2026-11-28 10:00:00 UTC)";
    const auto first = err.find(removed);
    ASSERT_NE(first, std::string::npos) << err;
    EXPECT_EQ(err.find("/next: the staging of a session", first + removed.size()),
              std::string::npos)
        << err;
    const auto saved = err.find("map saved to " + site + "/next/map");
    ASSERT_NE(saved, std::string::npos) << err;
    EXPECT_LT(first, saved) << err;  // removed before the session wrote into it
    EXPECT_NE(err.find(site + "/next is this session's staging (pid "), std::string::npos) << err;
    EXPECT_TRUE(fs::exists(store.staging_map_dir() + "/manifest.txt"));  // the first save, kept
    EXPECT_FALSE(fs::exists(store.staging_map_dir() + "/lm_earlier.bin"));
    EXPECT_EQ(map::read_staging_mark(site).pid, long(host.pid()));

    host.signal(SIGTERM);
    ASSERT_EQ(host.wait(60), 0) << host.err();
    EXPECT_NE(host.err().find("saved site version (site): " + site +
                              "/versions/v0002 (v0002: 0 local maps added"),
              std::string::npos)
        << host.err();
    const auto versions = store.versions();
    ASSERT_EQ(versions.size(), 2u);
    EXPECT_TRUE(versions[1].intact) << versions[1].problem;
    EXPECT_FALSE(fs::exists(versions[1].dir + "/session"));
}

TEST_F(SitePipeline, NothingStagedIsNotSavedAndThePreviousVersionStays) {
    const std::string site = path("site");
    make_first_version(site);
    Process host({kHost, config(173, site)}, path("host"));
    ASSERT_TRUE(host.wait_for_log("the session starts from v0001", 60)) << host.err();
    host.signal(SIGTERM);
    EXPECT_EQ(host.wait(60), 4) << host.err();
    EXPECT_NE(host.err().find("NOT saved: site version (site)"), std::string::npos) << host.err();
    EXPECT_NE(host.err().find("nothing committed, v0001 stays the newest version"),
              std::string::npos)
        << host.err();
    EXPECT_EQ(map::SiteStore(site).versions().size(), 1u);
}

TEST_F(SitePipeline, AnUnknownNamedVersionIsRefusedInOneLine) {
    const std::string site = path("site");
    make_first_version(site);
    const std::string cfg = write("named.yaml",
                                  "domain_id: 174\ndds: {interfaces: [lo], multicast: false, "
                                  "peers: [127.0.0.1]}\ncomponents:\n  - name: site\n    type: "
                                  "site\n    params: {site_dir: " +
                                      site + ", site_version: v0009}\n");
    Process host({kHost, cfg}, path("host"));
    EXPECT_EQ(host.wait(60), 2) << host.err();
    EXPECT_NE(host.err().find("no version v0009 (known: v0001)"), std::string::npos) << host.err();
}

TEST_F(SitePipeline, LocalisationOnANewSiteSaysThereIsNoMapYet) {
    const std::string site = path("site");
    map::write_anchor(site, map::anchor_from_transform({100, 200, 10}, 0, 0, 90));
    const std::string loc =
        "  - name: localisation\n    type: localisation\n    params: "
        "{site_dir: " +
        site + "}\n";
    Process host({kHost, config(175, site, loc)}, path("host"));
    ASSERT_TRUE(host.wait_for_log("the session starts from none (a new site)", 60)) << host.err();
    EXPECT_NE(host.err().find("new site: no map yet, nothing to localise on until the next "
                              "session"),
              std::string::npos)
        << host.err();
    EXPECT_NE(host.err().find("anchored (" + site + "/anchor.yaml)"), std::string::npos)
        << host.err();
    host.signal(SIGTERM);
    EXPECT_EQ(host.wait(60), 4) << host.err();  // nothing staged: no version
    EXPECT_NE(host.err().find("the site still has no version"), std::string::npos) << host.err();

    // A damaged anchor refuses the localisation in one line.
    std::ofstream(map::anchor_file(site), std::ios::app) << "scale: 2\n";
    Process again({kHost, config(176, site, loc)}, path("again"));
    EXPECT_EQ(again.wait(60), 2) << again.err();
    EXPECT_NE(again.err().find("anchor.yaml: line 8 at byte"), std::string::npos) << again.err();
}
