#pragma once
// Sites for the site_sync tests: a base station's site with two versions (the second changes one
// local map, adds one, and has a new graph, keyframes and maintained map; the rest hard links) and
// a robot's site holding a copy of the first.
#include <filesystem>
#include <string>

#include "map/core/map_store.hpp"
#include "map/core/site_store.hpp"
#include "map/core/site_test_maps.hpp"

namespace ltm::site_sync::test {

namespace fs = std::filesystem;

inline map::SiteVersion session(map::SiteStore& site, const map::MapData& map,
                                std::uint32_t maintained_fill) {
    const std::optional<map::SiteVersion> start = site.start_version("");
    map::SaveOptions options;
    if (start) options.link_from = start->map_dir();
    map::save_map(site.staging_map_dir(), map, options);
    map::test::write_maintained_map(site.staging_maintained_map_file(), maintained_fill);
    return site.commit(map::measure_version(site.staging_map_dir(), start ? start->map_dir() : "",
                                            start ? start->name : ""),
                       10);
}

// The base station's site: v0001 of 4 local maps (2000 voxels each), v0002 one more and one
// changed. Returns its folder.
inline std::string base_site(const fs::path& root) {
    const fs::path site = root / "base";
    fs::remove_all(site);
    map::SiteStore store(site.string());
    map::MapData day1 = map::test::tiny_map(4, 2000);
    session(store, day1, 1);
    map::MapData day2 = map::test::tiny_map(5, 2000);
    day2.local_maps[1].data = map::test::tiny_local_map(1, 99, 2000);  // changed by maintenance
    session(store, day2, 2);
    return site.string();
}

// The robot's site: a copy of the base station's v0001 (its own inodes).
inline std::string robot_site(const fs::path& root, const std::string& base) {
    const fs::path site = root / "robot";
    fs::remove_all(site);
    fs::create_directories(site / "versions");
    fs::copy(fs::path(base) / "versions/v0001", site / "versions/v0001",
             fs::copy_options::recursive);
    return site.string();
}

}  // namespace ltm::site_sync::test
