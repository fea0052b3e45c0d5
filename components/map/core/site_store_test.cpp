// The site's versions: listed in order, commit (atomic, only from a whole staging) and pruning,
// damaged versions skipped or refused in one line, a kill -9 during a save, hard links for
// unchanged local maps, and the measured summary.
#include "map/core/site_store.hpp"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "common/core/io_error.hpp"
#include "map/core/map_store.hpp"
#include "map/core/site_check.hpp"
#include "map/core/site_staging.hpp"
#include "map/core/site_test_maps.hpp"

namespace ltm::map {
namespace {

namespace fs = std::filesystem;

fs::path fresh_site(const std::string& name) {
    const fs::path p = fs::path(LTM_BINARY_DIR) / "site_test" / name;
    fs::remove_all(p);
    return p;
}

// One session: `map` saved into the staging (linked to the start version's), committed.
SiteVersion session(SiteStore& site, const MapData& map, std::size_t keep = 10,
                    SaveStats* stats = nullptr, bool maintained = true) {
    const std::optional<SiteVersion> start = site.start_version("");
    SaveOptions options;
    if (start) options.link_from = start->map_dir();
    const SaveStats s = save_map(site.staging_map_dir(), map, options);
    if (stats) *stats = s;
    if (maintained) test::write_maintained_map(site.staging_maintained_map_file(), 7);
    VersionSummary summary = measure_version(site.staging_map_dir(), start ? start->map_dir() : "",
                                             start ? start->name : "");
    return site.commit(summary, keep);
}

std::vector<std::string> names(const std::vector<SiteVersion>& v) {
    std::vector<std::string> out;
    for (const SiteVersion& x : v) out.push_back(x.name);
    return out;
}

// Damages a local map only this version holds: a file shared by hard links with an older
// version is damaged in both (one inode), as damage on the disk would be.
void truncate_a_local_map(const std::string& map_dir) {
    for (const auto& e : fs::directory_iterator(fs::path(map_dir) / "local_maps")) {
        if (fs::hard_link_count(e.path()) != 1) continue;
        fs::resize_file(e.path(), fs::file_size(e.path()) / 2);
        return;
    }
    FAIL() << "no local map of its own in " << map_dir;
}

std::string one_line_error(const std::function<void()>& f) {
    try {
        f();
    } catch (const common::IoError& e) {
        return e.what();
    }
    return "(no error)";
}

TEST(SiteStore, NewSiteHasNoVersionAndCreatesNothing) {
    const fs::path dir = fresh_site("new");
    SiteStore site(dir.string());
    EXPECT_TRUE(site.versions().empty());
    EXPECT_FALSE(site.start_version("").has_value());
    EXPECT_FALSE(fs::exists(dir));
    const SiteSession s = resolve_site(dir.string(), "");
    EXPECT_FALSE(s.start.has_value());
    EXPECT_EQ(s.staging_map_dir, (dir / "next/map").string());
    EXPECT_EQ(s.staging_maintained_map_file, (dir / "next/maintenance/long_term_map.bin").string());
}

TEST(SiteStore, VersionsListedInOrderWithWhatEachChanged) {
    const fs::path dir = fresh_site("order");
    SiteStore site(dir.string());
    for (std::size_t n = 1; n <= 3; ++n) session(site, test::tiny_map(2 * n));
    const std::vector<SiteVersion> all = site.versions();
    EXPECT_EQ(names(all), (std::vector<std::string>{"v0001", "v0002", "v0003"}));
    for (const SiteVersion& v : all) EXPECT_TRUE(v.intact) << v.problem;
    EXPECT_FALSE(fs::exists(site.staging_dir()));
    const VersionSummary s =
        parse_version_text(common::read_file(all[2].summary_file(), "version.txt"), "version.txt");
    EXPECT_EQ(s.number, 3u);
    EXPECT_EQ(s.started_from, "v0002");
    EXPECT_EQ(s.local_maps, 6u);
    EXPECT_EQ(s.local_maps_added, 2u);
    EXPECT_EQ(s.keyframes_added, 4u);
    EXPECT_NEAR(s.trajectory_m, 15.0, 1e-9);  // keyframes at x = 40, 45, 50, 55
    EXPECT_EQ(s.keyframes_compared, 8u);
    EXPECT_EQ(s.shift_max_m, 0.0);
    EXPECT_GT(s.created, 0);
    EXPECT_EQ(site.start_version("")->name, "v0003");
    EXPECT_EQ(site.start_version("2")->name, "v0002");
    EXPECT_EQ(site.start_version("v0001")->name, "v0001");
}

TEST(SiteStore, SummaryMeasuresHowFarOldKeyframesMoved) {
    const fs::path dir = fresh_site("moved");
    SiteStore site(dir.string());
    session(site, test::tiny_map(3));
    MapData moved = test::tiny_map(3);
    moved.nodes[2].T_world_anchor = registration::test::xy_yaw(20.3, 0.4, 2.0);  // 0.5 m, 2 deg
    // Local map 1 updated (other voxels), local map 2's file unchanged: only its anchor moved.
    moved.local_maps[1].data = test::tiny_local_map(1, 99, 200);
    session(site, moved);
    const VersionSummary s = parse_version_text(
        common::read_file(site.versions()[1].summary_file(), "version.txt"), "version.txt");
    EXPECT_EQ(s.local_maps_added, 0u);
    EXPECT_EQ(s.local_maps_updated, 1u);
    EXPECT_EQ(s.keyframes_added, 0u);
    EXPECT_EQ(s.keyframes_compared, 6u);
    EXPECT_GT(s.shift_max_m, 0.5);  // the second keyframe of node 2, 5 m out, turned 2 deg
    EXPECT_NEAR(s.turn_max_deg, 2.0, 1e-6);
    EXPECT_GT(s.shift_mean_m, 0.1);
    EXPECT_LT(s.shift_mean_m, s.shift_max_m);
    EXPECT_NE(version_line(s).find("1 updated"), std::string::npos);
}

TEST(SiteStore, UnchangedLocalMapsAreHardLinksNotCopies) {
    const fs::path dir = fresh_site("links");
    SiteStore site(dir.string());
    const SiteVersion v1 = session(site, test::tiny_map(3));
    SaveStats stats;
    MapData grown = test::tiny_map(4);  // the same three, and one more
    const SiteVersion v2 = session(site, grown, 10, &stats, /*maintained=*/false);
    EXPECT_GE(stats.files_linked, 3u);  // three local maps (and the full keyframe chunks)
    std::size_t linked = 0;
    for (const auto& e : fs::directory_iterator(fs::path(v2.map_dir()) / "local_maps")) {
        struct stat st {};
        ASSERT_EQ(stat(e.path().c_str(), &st), 0);
        if (fs::exists(fs::path(v1.map_dir()) / "local_maps" / e.path().filename())) {
            EXPECT_EQ(st.st_nlink, 2u) << e.path();
            ++linked;
        } else {
            EXPECT_EQ(st.st_nlink, 1u) << e.path();
        }
    }
    EXPECT_EQ(linked, 3u);
    // No maintained map staged: the start version's is carried (linked), not lost.
    struct stat st {};
    ASSERT_EQ(stat(v2.maintained_map_file().c_str(), &st), 0);
    EXPECT_EQ(st.st_nlink, 2u);
    EXPECT_TRUE(site.versions()[1].intact);
    // Both load whole.
    EXPECT_TRUE(load_map(v1.map_dir()).refused.empty());
    EXPECT_EQ(load_map(v2.map_dir()).map.local_maps.size(), 4u);
}

TEST(SiteStore, LinkingFallsBackToWritingWhenTheSourceIsNotThere) {
    const fs::path dir = fresh_site("nolink");
    SaveOptions options;
    options.link_from = (dir / "absent").string();
    const SaveStats s = save_map((dir / "map").string(), test::tiny_map(2), options);
    EXPECT_EQ(s.files_linked, 0u);
    EXPECT_EQ(check_map_dir((dir / "map").string()), "");
}

TEST(SiteStore, CommitRefusesAMissingOrDamagedStagingAndChangesNothing) {
    const fs::path dir = fresh_site("refuse");
    SiteStore site(dir.string());
    EXPECT_NE(one_line_error([&] { site.commit({}, 10); }).find("no staging"), std::string::npos);
    session(site, test::tiny_map(2));
    save_map(site.staging_map_dir(), test::tiny_map(3));
    truncate_a_local_map(site.staging_map_dir());
    const std::string error = one_line_error([&] { site.commit({}, 10); });
    EXPECT_NE(error.find("not whole"), std::string::npos) << error;
    EXPECT_NE(error.find("truncated"), std::string::npos) << error;
    EXPECT_EQ(error.find('\n'), std::string::npos);
    EXPECT_EQ(names(site.versions()), std::vector<std::string>{"v0001"});
    EXPECT_TRUE(fs::exists(site.staging_dir()));  // left for a look; the next session removes it
    EXPECT_FALSE(claim_staging(dir.string())->removed().empty());
    EXPECT_FALSE(fs::exists(site.staging_map_dir()));
    // A damaged maintained map is refused too.
    save_map(site.staging_map_dir(), test::tiny_map(3));
    test::write_maintained_map(site.staging_maintained_map_file(), 3);
    {
        std::fstream f(site.staging_maintained_map_file(),
                       std::ios::in | std::ios::out | std::ios::binary);
        f.seekp(20);
        f.put('\x55');
    }
    EXPECT_NE(one_line_error([&] { site.commit({}, 10); }).find("CRC-32"), std::string::npos);
    EXPECT_EQ(site.versions().size(), 1u);
}

TEST(SiteStore, PruningKeepsTheNewestAndTheStartWhileItIsTheOnlyIntactOlderOne) {
    const fs::path dir = fresh_site("prune");
    SiteStore site(dir.string());
    for (std::size_t n = 1; n <= 4; ++n) session(site, test::tiny_map(n + 1), 2);
    EXPECT_EQ(names(site.versions()), (std::vector<std::string>{"v0003", "v0004"}));
    EXPECT_EQ(site.pruned(), std::vector<std::string>{"v0002"});
    // v0004 damaged: the next session starts on v0003; with keep 1, v0003 stays (the only intact
    // older one), v0004 goes.
    truncate_a_local_map(site.versions()[1].map_dir());
    const SiteVersion v5 = session(site, test::tiny_map(6), 1);
    EXPECT_EQ(v5.name, "v0005");
    EXPECT_EQ(names(site.versions()), (std::vector<std::string>{"v0003", "v0005"}));
    EXPECT_EQ(site.start_version("")->name, "v0005");
    EXPECT_EQ(load_map(site.versions()[0].map_dir()).map.local_maps.size(), 4u);
}

TEST(SiteStore, NewestDamagedStartsOnThePreviousIntactOneAndSaysSo) {
    const fs::path dir = fresh_site("damaged");
    SiteStore site(dir.string());
    for (std::size_t n = 1; n <= 3; ++n) session(site, test::tiny_map(n + 1));
    truncate_a_local_map(site.versions()[2].map_dir());
    fs::remove(fs::path(site.versions()[1].map_dir()) / "manifest.txt");
    std::vector<std::string> notes;
    const std::optional<SiteVersion> start = site.start_version("", &notes);
    ASSERT_TRUE(start.has_value());
    EXPECT_EQ(start->name, "v0001");
    ASSERT_EQ(notes.size(), 2u);
    EXPECT_EQ(notes[0].rfind("v0003 is damaged (local_maps/lm_", 0), 0u) << notes[0];
    EXPECT_NE(notes[0].find("starting on v0001"), std::string::npos) << notes[0];
    EXPECT_NE(notes[1].find("v0002 is damaged"), std::string::npos) << notes[1];
    EXPECT_NE(notes[1].find("manifest.txt: missing"), std::string::npos) << notes[1];
    const std::vector<SiteVersion> all = site.versions();
    EXPECT_TRUE(all[0].intact);
    EXPECT_FALSE(all[1].intact);
    EXPECT_FALSE(all[2].intact);
    // Nothing intact: a new site, said.
    fs::resize_file(fs::path(all[0].map_dir()) / "manifest.txt", 10);
    notes.clear();
    EXPECT_FALSE(site.start_version("", &notes).has_value());
    EXPECT_EQ(notes.size(), 3u);
}

TEST(SiteStore, ANamedVersionThatIsDamagedOrUnknownIsRefusedInOneLine) {
    const fs::path dir = fresh_site("named");
    SiteStore site(dir.string());
    session(site, test::tiny_map(2));
    session(site, test::tiny_map(3));
    truncate_a_local_map(site.versions()[1].map_dir());
    const std::string damaged = one_line_error([&] { site.start_version("v0002"); });
    EXPECT_NE(damaged.find("v0002 is damaged (local_maps/lm_"), std::string::npos) << damaged;
    const std::string unknown = one_line_error([&] { resolve_site(dir.string(), "7"); });
    EXPECT_NE(unknown.find("no version v0007 (known: v0001, v0002)"), std::string::npos) << unknown;
    const std::string bad = one_line_error([&] { site.start_version("latest"); });
    EXPECT_NE(bad.find("not a version name"), std::string::npos) << bad;
    for (const std::string& e : {damaged, unknown, bad}) EXPECT_EQ(e.find('\n'), std::string::npos);
    EXPECT_EQ(site.start_version("1")->name, "v0001");
}

// A session killed (SIGKILL) while it saves a large map into the staging: every version stays
// whole, the next session starts on the previous one and removes the dead one's staging.
TEST(SiteStore, KillDuringASaveLeavesThePreviousVersionLoadable) {
    const fs::path dir = fresh_site("kill");
    SiteStore site(dir.string());
    session(site, test::tiny_map(2));
    int ready[2];
    ASSERT_EQ(pipe(ready), 0);
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        close(ready[0]);
        const auto claim = claim_staging(dir.string());  // as a session's writers do
        MapWriter writer(site.staging_map_dir());
        for (std::uint32_t round = 0;; ++round) {  // until killed: always in the middle of a save
            writer.save(test::tiny_map(12, 3000, round + 2));
            if (round == 0 && write(ready[1], "x", 1) != 1) _exit(1);
        }
    }
    close(ready[1]);
    char byte = 0;
    ASSERT_EQ(read(ready[0], &byte, 1), 1);  // the child's first save is done, others under way
    close(ready[0]);
    ASSERT_EQ(kill(child, SIGKILL), 0);
    int status = 0;
    ASSERT_EQ(waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFSIGNALED(status));

    const std::optional<SiteVersion> start = site.start_version("");
    ASSERT_TRUE(start.has_value());
    EXPECT_EQ(start->name, "v0001");
    const LoadedMap loaded = load_map(start->map_dir());
    EXPECT_TRUE(loaded.refused.empty());
    EXPECT_EQ(loaded.map.local_maps.size(), 2u);
    EXPECT_NE(claim_staging(dir.string())->removed().find("(pid " + std::to_string(child)),
              std::string::npos);
    EXPECT_EQ(session(site, test::tiny_map(3)).name, "v0002");
}

TEST(VersionSummary, TextRoundTripAndDamage) {
    VersionSummary s;
    s.number = 4;
    s.created = 1795810503;
    s.started_from = "v0003";
    s.session = 3;
    s.local_maps = 48;
    s.local_maps_added = 3;
    s.keyframes_added = 120;
    s.trajectory_m = 512.25;
    s.voxels_removed = 1234;
    s.shift_max_m = 0.012;
    const VersionSummary r = parse_version_text(write_version_text(s) + "future_key 1\n", "v");
    EXPECT_EQ(r.number, 4u);
    EXPECT_EQ(r.started_from, "v0003");
    EXPECT_EQ(r.trajectory_m, 512.25);
    EXPECT_EQ(r.voxels_removed, std::optional<std::uint64_t>(1234));
    EXPECT_FALSE(r.voxels_added.has_value());
    EXPECT_EQ(version_date(s.created), "2026-11-27 20:15 UTC");
    EXPECT_NE(version_line(r).find("1234 voxels removed, ? added"), std::string::npos);
    const std::string error = one_line_error(
        [] { parse_version_text("ltm_site_version 1\nlocal_maps x3\n", "version.txt"); });
    EXPECT_EQ(error, "version.txt: line 2 at byte 19: local_maps: 'x3' is not a valid value");
}

}  // namespace
}  // namespace ltm::map
