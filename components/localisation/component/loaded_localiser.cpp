#include "localisation/component/loaded_localiser.hpp"

#include <chrono>
#include <cstdio>

#include "localisation/core/map_pages.hpp"

namespace ltm::localisation {

LoadedLocaliser load_localiser(const std::string& dir, const LocalisationMapConfig& map_config,
                               const LocaliserConfig& config, bool with_global) {
    const auto t0 = std::chrono::steady_clock::now();
    LoadedLocaliser l;
    l.dir = dir;
    // Paged (neighbourhood.radius > 0, a map above neighbourhood.page_above_mb): the voxels stay
    // in `dir`; tracking registers to the local
    // maps near the pose, read as the robot moves (the first neighbourhood around the map's first
    // keyframe; the pose's once it has one), a global query to those near its initial poses.
    l.map = load_localisation_map(dir, map_config, &l.refused, config.neighbourhood.radius,
                                  config.neighbourhood.page_above_mb);
    l.localiser = std::make_unique<Localiser>(l.map, config);
    if (l.map->paged()) {
        l.localiser->set_neighbourhood(std::make_shared<NeighbourhoodBuilder>(
            l.map->pages(), config.neighbourhood,
            l.map->keyframes().front().T_map_lidar.translation()));
    }
    if (with_global) {
        // The query's own (it keeps scratch state): never shared with tracking.
        l.global = std::make_shared<GlobalLocaliser>(l.map, config.global);
        l.localiser->set_global_elsewhere(true);
    }
    l.load_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return l;
}

std::string LoadedLocaliser::line() const {
    char text[300];
    std::snprintf(
        text, sizeof text, "map %s: %zu keyframes, %zu local maps, %zu voxels, loaded in %.2f s",
        dir.c_str(), map->keyframes().size(), map->local_maps(), map->voxel_count(), load_s);
    return text;
}

}  // namespace ltm::localisation
