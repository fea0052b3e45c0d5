#include "evaluation/cli/lifelong_inputs.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/core/io_error.hpp"
#include "map/core/map_store.hpp"
#include "map/core/merged_voxels.hpp"

namespace ltm::eval::cli {

std::vector<double> read_kidnap_stamps(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw common::IoError(path, "cannot read");
    std::vector<double> out;
    std::string line;
    for (int n = 1; std::getline(in, line); ++n) {
        const auto hash = line.find('#');
        if (hash != std::string::npos) line.resize(hash);
        if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
        std::istringstream s(line);
        long frame = 0;
        double stamp = 0.0;
        if (!(s >> frame >> stamp))
            throw common::IoError(path, "line " + std::to_string(n) + ": expected `frame stamp`");
        out.push_back(stamp);
    }
    return out;
}

ProcessUsage read_time_report(const std::string& path) {
    ProcessUsage u;
    std::ifstream in(path);
    if (!in) return u;
    bool rss = false, user = false, sys = false;
    std::string line;
    auto value_after_colon = [](const std::string& l) {
        return std::stod(l.substr(l.rfind(':') + 1));
    };
    while (std::getline(in, line)) {
        try {
            if (line.find("Maximum resident set size (kbytes):") != std::string::npos) {
                u.max_rss_mb = value_after_colon(line) / 1024.0;
                rss = true;
            } else if (line.find("User time (seconds):") != std::string::npos) {
                u.cpu_s += value_after_colon(line);
                user = true;
            } else if (line.find("System time (seconds):") != std::string::npos) {
                u.cpu_s += value_after_colon(line);
                sys = true;
            }
        } catch (const std::exception&) {
            return ProcessUsage{};
        }
    }
    u.valid = rss && user && sys;
    return u;
}

std::uintmax_t bytes_on_disk(const std::string& path) {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (path.empty() || !fs::exists(path, ec)) return 0;
    if (fs::is_regular_file(path, ec)) return fs::file_size(path, ec);
    std::uintmax_t total = 0;
    for (fs::recursive_directory_iterator
             it(path, fs::directory_options::follow_directory_symlink, ec),
         end;
         !ec && it != end; it.increment(ec)) {
        if (it->is_regular_file(ec)) total += it->file_size(ec);
    }
    return total;
}

std::vector<Eigen::Vector3d> map_voxel_centres(const std::string& dir,
                                               const Eigen::Isometry3d& T_world_map,
                                               double min_health, double min_planarity) {
    const map::LoadedMap loaded = map::load_map(dir);
    map::MergedVoxelsFilter filter;
    filter.min_health = min_health;
    filter.min_planarity = min_planarity;
    const map::MergedVoxels merged = map::merge_voxels(loaded.map, filter);
    std::vector<Eigen::Vector3d> out;
    if (!merged.voxels) return out;
    out.reserve(merged.voxels->voxels.size());
    for (const auto& v : merged.voxels->voxels)
        out.push_back(T_world_map * v.centre.cast<double>());
    return out;
}

}  // namespace ltm::eval::cli
