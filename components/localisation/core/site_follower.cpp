#include "localisation/core/site_follower.hpp"

#include <algorithm>
#include <filesystem>
#include <utility>

#include "map/core/site_check.hpp"
#include "map/core/site_store.hpp"

namespace ltm::localisation {

namespace fs = std::filesystem;

SiteFollower::SiteFollower(std::string site_dir, std::uint32_t in_use)
    : site_dir_(std::move(site_dir)), in_use_(in_use) {}

std::optional<map::SiteVersion> SiteFollower::newer(std::vector<std::string>* notes) {
    std::vector<std::uint32_t> found;
    std::error_code ec;
    const fs::path root = fs::path(site_dir_) / "versions";
    for (const fs::directory_entry& e : fs::directory_iterator(root, ec)) {
        const std::uint32_t n = map::version_number(e.path().filename().string());
        if (n > in_use_ && !damaged_.count(n) && e.is_directory(ec)) found.push_back(n);
    }
    std::sort(found.rbegin(), found.rend());  // newest first
    for (const std::uint32_t n : found) {
        map::SiteVersion v;
        v.number = n;
        v.name = map::version_name(n);
        v.dir = (root / v.name).string();
        v.problem = map::check_map_dir(v.map_dir());
        if (v.problem.empty()) v.problem = map::check_maintained_map_file(v.maintained_map_file());
        v.intact = v.problem.empty();
        if (v.intact) return v;
        damaged_.insert(n);
        if (notes) notes->push_back(v.name + " is damaged (" + v.problem + "): not used");
    }
    return std::nullopt;
}

}  // namespace ltm::localisation
