// A site's versions on a disk that fills up (issue 28, item 4): a save or a commit the disk
// refuses is one line, the version before stays the newest and loads whole, nothing is half
// committed, and once there is room again the next session commits. On a small tmpfs (root);
// skipped where mounting is refused.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "common/core/io_error.hpp"
#include "common/core/small_disk_for_tests.hpp"
#include "map/core/map_store.hpp"
#include "map/core/site_staging.hpp"
#include "map/core/site_store.hpp"
#include "map/core/site_test_maps.hpp"

namespace ltm::map {
namespace {

namespace fs = std::filesystem;

// Fills the disk: a file written in 16 KiB pieces until the disk refuses one.
void fill(const std::string& path) {
    std::FILE* f = std::fopen(path.c_str(), "wb");
    ASSERT_NE(f, nullptr);
    const std::string piece(16 * 1024, 'f');
    while (std::fwrite(piece.data(), 1, piece.size(), f) == piece.size() && std::fflush(f) == 0) {
    }
    std::fclose(f);
}

// The staging saved from `map` (linked to the start version's) and measured.
VersionSummary stage(SiteStore& site, const MapData& map) {
    const std::optional<SiteVersion> start = site.start_version("");
    SaveOptions options;
    if (start) options.link_from = start->map_dir();
    save_map(site.staging_map_dir(), map, options);
    test::write_maintained_map(site.staging_maintained_map_file(), 7);
    return measure_version(site.staging_map_dir(), start ? start->map_dir() : "",
                           start ? start->name : "");
}

void expect_v0001_whole(SiteStore& site) {
    const std::vector<SiteVersion> versions = site.versions();
    ASSERT_EQ(versions.size(), 1u);
    EXPECT_EQ(versions[0].name, "v0001");
    const std::optional<SiteVersion> start = site.start_version("");
    ASSERT_TRUE(start.has_value());
    EXPECT_EQ(start->name, "v0001");
    const LoadedMap loaded = load_map(start->map_dir());
    EXPECT_TRUE(loaded.refused.empty());
    EXPECT_EQ(loaded.map.local_maps.size(), 2u);
}

TEST(SiteFullDisk, ASaveTheDiskRefusesIsOneLineAndThePreviousVersionStays) {
    common::SmallDisk disk("site_save", 4 << 20);
    if (!disk.mounted()) GTEST_SKIP() << disk.why();
    SiteStore site(disk.path() + "/site");
    site.commit(stage(site, test::tiny_map(2)), 10);
    fill(disk.path() + "/filler");
    std::string error;
    try {
        stage(site, test::tiny_map(12, 3000, 2));
    } catch (const common::IoError& e) {
        error = e.what();
    }
    ASSERT_FALSE(error.empty()) << "the full disk took the save";
    EXPECT_EQ(error.find('\n'), std::string::npos) << error;
    EXPECT_NE(error.find("No space left"), std::string::npos) << error;
    expect_v0001_whole(site);
    // Room again: the next session starts from v0001 (the stale staging removed) and commits.
    fs::remove(disk.path() + "/filler");
    EXPECT_FALSE(claim_staging(disk.path() + "/site")->removed().empty());
    EXPECT_EQ(site.commit(stage(site, test::tiny_map(3)), 10).name, "v0002");
    EXPECT_TRUE(load_map(site.start_version("")->map_dir()).refused.empty());
}

TEST(SiteFullDisk, ACommitTheDiskRefusesLeavesNoHalfVersion) {
    common::SmallDisk disk("site_commit", 4 << 20);
    if (!disk.mounted()) GTEST_SKIP() << disk.why();
    SiteStore site(disk.path() + "/site");
    site.commit(stage(site, test::tiny_map(2)), 10);
    const VersionSummary summary = stage(site, test::tiny_map(3));
    fill(disk.path() + "/filler");  // the staging is saved; the commit's own writes are refused
    std::string error;
    try {
        site.commit(summary, 10);
    } catch (const common::IoError& e) {
        error = e.what();
    }
    ASSERT_FALSE(error.empty()) << "the full disk took the commit";
    EXPECT_EQ(error.find('\n'), std::string::npos) << error;
    expect_v0001_whole(site);
    fs::remove(disk.path() + "/filler");
    EXPECT_EQ(site.commit(summary, 10).name, "v0002");  // the staging was left whole
    EXPECT_TRUE(load_map(site.start_version("")->map_dir()).refused.empty());
}

}  // namespace
}  // namespace ltm::map
