#include "link/core/site_watermarks.hpp"

#include <filesystem>
#include <utility>

#include "common/core/io_error.hpp"
#include "map/core/link_applied.hpp"
#include "map/core/site_check.hpp"
#include "map/core/site_store.hpp"

namespace ltm::link {
namespace fs = std::filesystem;

namespace {
SiteWatermarks::Through record_of(const std::string& map_dir, const std::string& robot,
                                  std::string* note) {
    const map::LinkApplied all = map::read_link_applied(map_dir, note);
    const auto it = all.find(robot);
    return it == all.end() ? SiteWatermarks::Through{} : it->second;
}
}  // namespace

SiteWatermarks::SiteWatermarks(std::string site_dir, const std::string& version, std::string robot)
    : site_dir_(std::move(site_dir)), robot_(std::move(robot)) {
    const std::optional<map::SiteVersion> start =
        map::SiteStore(site_dir_).start_version(version, nullptr);
    if (!start) return;  // a new site
    start_name_ = start->name;
    seen_ = start->number;
    start_ = record_of(start->map_dir(), robot_, &start_note_);
}

std::optional<SiteWatermarks::Newer> SiteWatermarks::poll(std::string* note) {
    // Only the folder names: a version is checked once, when it is the newest seen.
    std::uint32_t newest = 0;
    std::error_code ec;
    for (const fs::directory_entry& e : fs::directory_iterator(site_dir_ + "/versions", ec))
        newest = std::max(newest, map::version_number(e.path().filename().string()));
    if (newest <= seen_) return std::nullopt;
    seen_ = newest;
    const std::string name = map::version_name(newest);
    const std::string dir = site_dir_ + "/versions/" + name;
    std::string problem = map::check_map_dir(dir + "/map");
    if (problem.empty())
        problem = map::check_maintained_map_file(dir + "/maintenance/long_term_map.bin");
    if (!problem.empty()) {
        if (note) *note = name + " is not whole (" + problem + "): its record is not used";
        return std::nullopt;
    }
    try {
        return Newer{name, record_of(dir + "/map", robot_, note)};
    } catch (const common::IoError& e) {
        if (note) *note = name + ": " + e.what() + ": its record is not used";
        return std::nullopt;
    }
}

}  // namespace ltm::link
