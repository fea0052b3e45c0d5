#include "localisation/core/map_pages.hpp"

#include <algorithm>
#include <unordered_map>

#include "common/core/io_error.hpp"
#include "map/core/merged_voxels.hpp"

namespace ltm::localisation {

MapPages::MapPages(std::string dir, const LocalisationMapConfig& config)
    : dir_(std::move(dir)), config_(config) {
    map::LoadedMap loaded = map::load_map(dir_, false);
    skeleton_ = std::move(loaded.map);
    format_version_ = loaded.format_version;
    std::unordered_map<std::uint64_t, Eigen::Vector3d> anchors;
    for (const map::PoseGraphNode& n : skeleton_.nodes) {
        graph_nodes_.insert(n.id);
        anchors[n.id] = n.T_world_anchor.translation();
    }
    for (const map::ManifestEntry& e : loaded.local_map_files) {
        const auto a = anchors.find(e.node);
        if (a == anchors.end()) continue;  // not placed: merge_voxels leaves it out as well
        files_.push_back({e, a->second});
    }
    std::sort(files_.begin(), files_.end(),
              [](const File& a, const File& b) { return a.entry.node < b.entry.node; });
}

std::vector<std::uint64_t> MapPages::nodes_near(const Eigen::Vector3d& centre,
                                                double radius) const {
    std::vector<std::uint64_t> out;
    const double r2 = radius * radius;
    for (const File& f : files_) {
        if ((f.anchor - centre).head<2>().squaredNorm() <= r2) out.push_back(f.entry.node);
    }
    return out;
}

std::shared_ptr<const Neighbourhood> MapPages::build(const Eigen::Vector3d& centre, double radius,
                                                     std::vector<std::string>* refused) const {
    auto n = std::make_shared<Neighbourhood>();
    n->centre = centre;
    n->radius = radius;
    map::MapData part;
    part.nodes = skeleton_.nodes;
    const double r2 = radius * radius;
    for (const File& f : files_) {
        if ((f.anchor - centre).head<2>().squaredNorm() > r2) continue;
        try {
            part.local_maps.push_back(
                map::load_local_map(dir_, f.entry, format_version_, graph_nodes_));
            n->nodes.push_back(f.entry.node);
        } catch (const common::IoError& e) {  // unreadable or damaged: the rest is used
            if (refused) refused->push_back(e.what());
        }
    }
    n->complete = n->nodes.size() == files_.size();
    map::MergedVoxels merged = map::merge_voxels(part, {config_.min_health, config_.min_planarity});
    part.local_maps.clear();  // the files' voxels go; the merged ones stay
    n->target = std::make_shared<const registration::RegistrationTarget>(
        registration::make_registration_target(*merged.voxels, config_.min_planarity,
                                               config_.coarse_factor));
    n->voxels = std::move(merged.voxels);
    return n;
}

}  // namespace ltm::localisation
