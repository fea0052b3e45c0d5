#pragma once
// A saved map loaded into a localiser: the map (with the settings of the sensor's preset), its
// Localiser, and with `with_global` the global localiser a thread of its own answers queries on
// (its localiser set to ask it: Localiser::set_global_elsewhere). The component's map at start and
// each newer site version (version_loader.hpp) are loaded so.
#include <memory>
#include <string>
#include <vector>

#include "localisation/core/global_localiser.hpp"
#include "localisation/core/localiser.hpp"

namespace ltm::localisation {

struct LoadedLocaliser {
    std::shared_ptr<const LocalisationMap> map;
    std::unique_ptr<Localiser> localiser;
    std::shared_ptr<GlobalLocaliser> global;  // with_global only
    std::vector<std::string> refused;         // parts of the map left out, one line each
    double load_s = 0.0;                      // wall time to load the map and build the localiser
    std::string line() const;                 // "map DIR: N keyframes, ..., loaded in S s"
    std::string dir;
};

// Throws (common::IoError, ConfigError) with the reason when the map does not load.
LoadedLocaliser load_localiser(const std::string& dir, const LocalisationMapConfig& map_config,
                               const LocaliserConfig& config, bool with_global);

}  // namespace ltm::localisation
