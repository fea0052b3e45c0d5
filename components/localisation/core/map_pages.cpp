#include "localisation/core/map_pages.hpp"

#include <algorithm>
#include <optional>
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

namespace {

bool near_any(const Eigen::Vector3d& anchor, const std::vector<Eigen::Vector3d>& centres,
              double r2) {
    for (const Eigen::Vector3d& c : centres) {
        if ((anchor - c).head<2>().squaredNorm() <= r2) return true;
    }
    return false;
}

}  // namespace

std::vector<std::uint64_t> MapPages::nodes_near(const Eigen::Vector3d& centre,
                                                double radius) const {
    return nodes_near(std::vector<Eigen::Vector3d>{centre}, radius);
}

std::vector<std::uint64_t> MapPages::nodes_near(const std::vector<Eigen::Vector3d>& centres,
                                                double radius) const {
    std::vector<std::uint64_t> out;
    const double r2 = radius * radius;
    for (const File& f : files_) {
        if (near_any(f.anchor, centres, r2)) out.push_back(f.entry.node);
    }
    return out;
}

std::shared_ptr<const Neighbourhood> MapPages::build(const Eigen::Vector3d& centre, double radius,
                                                     std::vector<std::string>* refused) const {
    return build(std::vector<Eigen::Vector3d>{centre}, radius, refused);
}

std::shared_ptr<const Neighbourhood> MapPages::build(const std::vector<Eigen::Vector3d>& centres,
                                                     double radius,
                                                     std::vector<std::string>* refused) const {
    auto n = std::make_shared<Neighbourhood>();
    n->centre = centres.empty() ? Eigen::Vector3d::Zero() : centres.front();
    n->radius = radius;
    // One local map in memory at a time: each is merged and freed before the next is read. The
    // lattice is the largest voxel size of those held (merge_voxels'): a larger one met later
    // starts the merge again on its lattice (maps are made with one voxel size: never, in
    // practice).
    std::unordered_map<std::uint64_t, Eigen::Isometry3d> anchors;
    for (const map::PoseGraphNode& node : skeleton_.nodes) anchors[node.id] = node.T_world_anchor;
    const double r2 = radius * radius;
    float voxel_size = 0.0f;
    std::optional<map::VoxelMerger> merger;
    std::vector<std::string> failed;
    for (bool again = true; again;) {
        again = false;
        n->nodes.clear();
        failed.clear();
        merger.emplace(voxel_size,
                       map::MergedVoxelsFilter{config_.min_health, config_.min_planarity});
        for (const File& f : files_) {
            if (!near_any(f.anchor, centres, r2)) continue;
            map::StoredLocalMap lm;
            try {
                lm = map::load_local_map(dir_, f.entry, format_version_, graph_nodes_);
            } catch (const common::IoError& e) {  // unreadable or damaged: the rest is used
                failed.push_back(e.what());
                continue;
            }
            if (!lm.data) continue;
            if (lm.data->voxel_size > voxel_size) {
                const bool first = voxel_size == 0.0f;
                voxel_size = lm.data->voxel_size;
                if (!first) {
                    again = true;
                    break;
                }
                merger.emplace(voxel_size,
                               map::MergedVoxelsFilter{config_.min_health, config_.min_planarity});
            }
            merger->add(lm, anchors.at(f.entry.node));
            n->nodes.push_back(f.entry.node);
        }
    }
    if (refused) refused->insert(refused->end(), failed.begin(), failed.end());
    n->complete = n->nodes.size() == files_.size();
    map::MergedVoxels merged = merger->finish();
    n->target = std::make_shared<const registration::RegistrationTarget>(
        registration::make_registration_target(*merged.voxels, config_.min_planarity,
                                               config_.coarse_factor));
    n->voxels = std::move(merged.voxels);
    return n;
}

}  // namespace ltm::localisation
