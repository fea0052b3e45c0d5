#include "localisation/core/map_pages.hpp"

#include <algorithm>
#include <optional>
#include <unordered_map>

#include "common/core/io_error.hpp"
#include "map/core/merged_voxels.hpp"

namespace ltm::localisation {

MapPages::MapPages(std::string dir, const LocalisationMapConfig& config)
    : MapPages(dir, map::load_map(dir, false), config) {}

MapPages::MapPages(std::string dir, const map::LoadedMap& loaded,
                   const LocalisationMapConfig& config)
    : dir_(std::move(dir)), config_(config) {
    format_version_ = loaded.format_version;
    std::unordered_map<std::uint64_t, Eigen::Isometry3d> anchors;
    for (const map::PoseGraphNode& n : loaded.map.nodes) {
        graph_nodes_.insert(n.id);
        anchors[n.id] = n.T_world_anchor;
    }
    for (const map::ManifestEntry& e : loaded.local_map_files) {
        const auto a = anchors.find(e.node);
        if (a == anchors.end()) continue;  // not placed: merge_voxels leaves it out as well
        File f;
        f.entry = e;
        f.T_world_anchor = a->second;
        f.anchor = a->second.translation();
        files_.push_back(std::move(f));
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

template <class Take>
map::MergedVoxels MapPages::merge(Take&& take, std::vector<std::uint64_t>* nodes,
                                  std::vector<std::string>* refused) const {
    // One local map in memory at a time: each is merged and freed before the next is read. The
    // lattice is the largest voxel size of those held (merge_voxels'): a larger one met later
    // starts the merge again on its lattice (maps are made with one voxel size: never, in
    // practice).
    float voxel_size = 0.0f;
    std::optional<map::VoxelMerger> merger;
    std::vector<std::string> failed;
    for (bool again = true; again;) {
        again = false;
        nodes->clear();
        failed.clear();
        merger.emplace(voxel_size,
                       map::MergedVoxelsFilter{config_.min_health, config_.min_planarity});
        for (const File& f : files_) {
            if (!take(f)) continue;
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
            merger->add(lm, f.T_world_anchor);
            nodes->push_back(f.entry.node);
        }
    }
    if (refused) refused->insert(refused->end(), failed.begin(), failed.end());
    return merger->finish();
}

map::MergedVoxels MapPages::merge_all(std::vector<std::string>* refused) const {
    std::vector<std::uint64_t> nodes;
    return merge([](const File&) { return true; }, &nodes, refused);
}

void MapPages::for_each_voxel(const std::function<void(const Eigen::Vector3f&, float)>& f,
                              std::vector<std::string>* refused) const {
    const map::MergedVoxelsFilter filter{config_.min_health, config_.min_planarity};
    for (const File& file : files_) {
        map::StoredLocalMap lm;
        try {
            lm = map::load_local_map(dir_, file.entry, format_version_, graph_nodes_);
        } catch (const common::IoError& e) {
            if (refused) refused->push_back(e.what());
            continue;
        }
        if (!lm.data) continue;
        const Eigen::Isometry3d T = file.T_world_anchor * lm.data->T_anchor_grid;
        const Eigen::Matrix3f R = T.linear().cast<float>();
        const Eigen::Vector3f t = T.translation().cast<float>();
        for (const common::VoxelData& v : lm.data->voxels) {
            if (map::merges(v, filter)) f(R * v.centre + t, lm.data->voxel_size);
        }
    }
}

std::shared_ptr<const Neighbourhood> MapPages::build(const std::vector<Eigen::Vector3d>& centres,
                                                     double radius,
                                                     std::vector<std::string>* refused) const {
    auto n = std::make_shared<Neighbourhood>();
    n->centre = centres.empty() ? Eigen::Vector3d::Zero() : centres.front();
    n->radius = radius;
    const double r2 = radius * radius;
    map::MergedVoxels merged =
        merge([&](const File& f) { return near_any(f.anchor, centres, r2); }, &n->nodes, refused);
    n->complete = n->nodes.size() == files_.size();
    n->target = std::make_shared<const registration::RegistrationTarget>(
        registration::make_registration_target(*merged.voxels, config_.min_planarity,
                                               config_.coarse_factor));
    n->voxels = std::move(merged.voxels);
    return n;
}

std::size_t Neighbourhood::memory_bytes() const {
    return sizeof(Neighbourhood) + nodes.capacity() * sizeof(std::uint64_t) +
           (voxels ? voxels->voxels.capacity() * sizeof(common::VoxelData) : 0) +
           (target ? target->memory_bytes() : 0);
}

}  // namespace ltm::localisation
