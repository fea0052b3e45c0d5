#include "localisation/core/site_follower.hpp"

#include <algorithm>
#include <filesystem>
#include <utility>

#include "map/core/site_check.hpp"

namespace ltm::localisation {
namespace {

namespace fs = std::filesystem;

// The number of a version folder's name ("v0003" -> 3), 0 when it is not one (as site_store).
std::uint32_t number_of(const std::string& name) {
    if (name.size() < 2 || name[0] != 'v' || name.size() > 10) return 0;
    std::uint64_t n = 0;
    for (std::size_t i = 1; i < name.size(); ++i) {
        if (name[i] < '0' || name[i] > '9') return 0;
        n = n * 10 + std::uint64_t(name[i] - '0');
    }
    return n > 0 && n <= 0xffffffffull ? std::uint32_t(n) : 0;
}

}  // namespace

SiteFollower::SiteFollower(std::string site_dir, std::uint32_t in_use)
    : site_dir_(std::move(site_dir)), in_use_(in_use) {}

std::optional<map::SiteVersion> SiteFollower::newer(std::vector<std::string>* notes) {
    std::vector<std::uint32_t> found;
    std::error_code ec;
    const fs::path root = fs::path(site_dir_) / "versions";
    for (const fs::directory_entry& e : fs::directory_iterator(root, ec)) {
        const std::uint32_t n = number_of(e.path().filename().string());
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
