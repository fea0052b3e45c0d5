#pragma once
// Where a localisation on a site (`site_dir`, map/core/site_store.hpp) starts: the start version's
// map (`site_version`, or the newest intact one), none on a new site (no version yet), and the
// site's anchor (map/core/site_anchor.hpp) when it has one. An unknown or damaged named version, or
// a damaged anchor, refuses the component in one line at its key (ConfigError).
#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "runtime/parameters.hpp"

namespace ltm::localisation {

struct SiteStart {
    std::string site_dir;
    std::string map_dir;             // empty: a new site
    std::uint32_t in_use = 0;        // the start version (0: none)
    std::string describe;            // the start version, for the log ("version 3 (...)")
    std::vector<std::string> notes;  // damaged versions passed over: warnings
    std::optional<Eigen::Isometry3d> T_site_map;  // the anchor's
    std::string anchor_file;
};

// The site `site_dir` names at `version` ("": the newest intact one).
SiteStart resolve_site_start(runtime::Parameters& params, const std::string& site_dir,
                             const std::string& version);

}  // namespace ltm::localisation
