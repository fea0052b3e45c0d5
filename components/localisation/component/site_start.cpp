#include "localisation/component/site_start.hpp"

#include "common/core/io_error.hpp"
#include "map/core/site_anchor.hpp"
#include "map/core/site_store.hpp"

namespace ltm::localisation {

SiteStart resolve_site_start(runtime::Parameters& params, const std::string& site_dir,
                             const std::string& version) {
    SiteStart start;
    start.site_dir = site_dir;
    map::SiteSession session;
    try {
        session = map::resolve_site(site_dir, version);
    } catch (const common::IoError& e) {
        params.fail(version.empty() ? "site_dir" : "site_version", e.what());
    }
    start.notes = session.notes;
    try {
        if (const auto anchor = map::read_anchor(site_dir)) {
            start.T_site_map = anchor->T_site_map;
            start.anchor_file = map::anchor_file(site_dir);
        }
    } catch (const common::IoError& e) {
        params.fail("site_dir", e.what());
    }
    if (session.start) {
        start.map_dir = session.start->map_dir();
        start.in_use = session.start->number;
        start.describe = session.describe();
    }
    return start;
}

}  // namespace ltm::localisation
