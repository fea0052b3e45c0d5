#include "localisation/core/localisation_map.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "common/core/config_check.hpp"
#include "common/core/io_error.hpp"
#include "localisation/core/map_features.hpp"
#include "localisation/core/map_pages.hpp"
#include "localisation/core/voxel_columns.hpp"
#include "map/core/map_store.hpp"
#include "map/core/merged_voxels.hpp"

namespace ltm::localisation {

namespace {

constexpr double kCoverageCell = 2.0;  // [m] cell of a paged map's coverage grid

}  // namespace

LocalisationMap::LocalisationMap(const map::MapData& map, const LocalisationMapConfig& config,
                                 std::shared_ptr<const MapPages> pages, double page_radius,
                                 std::vector<std::string>* refused)
    : index_(1) {
    if (map.keyframes.empty()) {
        throw common::ConfigError("map", "has no keyframes: nothing to localise against");
    }
    const bool paging = pages && page_radius > 0.0;
    const bool stored =
        map.localisation_descriptor_config.rings > 0 &&
        map.localisation_descriptor_config.kind == places::ScanContextKind::kMeanVariance;
    descriptor_config_ = stored ? map.localisation_descriptor_config : config.descriptor;
    feature_config_ = config.features;
    feature_map_config_ = config;
    coarse_voxel_size_ = 0.0;
    if (paging && stored) {
        // Never merged whole: each local map read once for the coverage grid, then let go.
        float size = 0.0f;
        pages->for_each_voxel(
            [&](const Eigen::Vector3f& c, float voxel_size) {
                coverage_.insert(coverage_key(c.x(), c.y()));
                size = std::max(size, voxel_size);
                ++voxel_count_;
            },
            refused);
        if (voxel_count_ == 0) {
            throw common::ConfigError("map", "has no usable voxels: nothing to register against");
        }
        voxel_size_ = size;
        local_maps_ = pages->local_maps();
        sessions_ = map.sessions.size();
    } else {
        // With pages: the local maps read from the directory one at a time (map holds none).
        index_voxels(pages ? pages->merge_all(refused)
                           : map::merge_voxels(map, {config.min_health, config.min_planarity}));
        if (voxels_->voxels.empty()) {
            throw common::ConfigError("map", "has no usable voxels: nothing to register against");
        }
        voxel_size_ = voxels_->voxel_size;
        voxel_count_ = voxels_->voxels.size();
        if (paging) index_coverage();  // a format-1 map: its descriptors need the voxels first
    }
    coarse_voxel_size_ =
        config.coarse_factor >= 2 ? voxel_size_ * config.coarse_factor : voxel_size_;
    if (!paging) {
        target_ = std::make_shared<const registration::RegistrationTarget>(
            registration::make_registration_target(*voxels_, config.min_planarity,
                                                   config.coarse_factor));
    }
    place_keyframes(map);
    // Paged: a global query makes the features of its places from the local maps it reads.
    if (config.local_features && !paging) features_ = make_map_features(voxels_->voxels, config);
    if (paging) {
        // The site's index stays; the voxels are in the map directory.
        pages_ = std::move(pages);
        page_radius_ = page_radius;
        columns_.reset();  // before the voxels it refers to
        voxels_.reset();
    }
}

LocalisationMap::~LocalisationMap() = default;

std::size_t LocalisationMap::memory_bytes() const {
    std::size_t n = keyframes_.capacity() * sizeof(MapKeyframe);
    for (const MapKeyframe& k : keyframes_) n += k.descriptor.memory_bytes();
    if (voxels_) n += voxels_->voxels.capacity() * sizeof(common::VoxelData);
    if (target_) n += target_->memory_bytes();
    n += features_.positions.capacity() * sizeof(Eigen::Vector3d);
    for (const places::ScanContext& d : features_.descriptors) n += d.memory_bytes();
    // A coverage cell: a 32-byte node and a bucket.
    n += coverage_.size() * 32 + coverage_.bucket_count() * sizeof(void*);
    return n;
}

std::uint64_t LocalisationMap::coverage_key(double x, double y) const {
    const auto cx = std::int64_t(std::floor(x / kCoverageCell));
    const auto cy = std::int64_t(std::floor(y / kCoverageCell));
    return (std::uint64_t(cx + (1 << 30)) << 32) | std::uint64_t(cy + (1 << 30));
}

void LocalisationMap::index_coverage() {
    for (const common::VoxelData& v : voxels_->voxels) {
        coverage_.insert(coverage_key(v.centre.x(), v.centre.y()));
    }
}

const common::LocalMapData& LocalisationMap::voxels() const {
    if (!voxels_) throw common::ConfigError("map", "is paged: its voxels are on disk");
    return *voxels_;
}

const registration::RegistrationTarget& LocalisationMap::target() const {
    if (!target_) throw common::ConfigError("map", "is paged: its voxels are on disk");
    return *target_;
}

std::shared_ptr<const registration::RegistrationTarget> LocalisationMap::target_around(
    const std::vector<Eigen::Vector3d>& positions) const {
    if (!pages_) return target_;
    return neighbourhood_around(positions)->target;
}

std::shared_ptr<const Neighbourhood> LocalisationMap::neighbourhood_around(
    const std::vector<Eigen::Vector3d>& positions) const {
    if (!pages_) return nullptr;
    const std::vector<std::uint64_t> want = pages_->nodes_near(positions, page_radius_);
    std::lock_guard<std::mutex> lock(around_mutex_);
    if (auto held = around_.lock();
        held && std::includes(held->nodes.begin(), held->nodes.end(), want.begin(), want.end()))
        return held;
    std::vector<std::string> refused;
    std::shared_ptr<const Neighbourhood> n = pages_->build(positions, page_radius_, &refused);
    if (n->nodes.empty() && !want.empty()) {
        throw common::IoError(pages_->dir(),
                              refused.empty() ? "no local map could be read" : refused.front());
    }
    around_ = n;
    return n;
}

places::LocalFeatures LocalisationMap::features_around(const Neighbourhood& n,
                                                       const std::vector<Eigen::Vector3d>& places,
                                                       double near) const {
    if (!n.voxels) return {};
    return make_map_features(n.voxels->voxels, feature_map_config_, &places, near);
}

places::LocalFeatures LocalisationMap::features_near_places(
    const std::vector<Eigen::Vector3d>& places, double radius, const Neighbourhood* around) const {
    places::LocalFeatures out;
    if (!has_features()) return out;
    const double r2 = radius * radius;
    if (pages_) {
        if (!around) return out;
        // A cell holds samples up to its half-diagonal from its centre.
        const places::LocalFeatures made = features_around(
            *around, places, radius + kFeatureCellHalfDiagonal * feature_map_config_.feature_cell);
        out.sample_spacing = made.sample_spacing;
        for (std::size_t k = 0; k < made.size(); ++k) {
            const bool in = std::any_of(places.begin(), places.end(), [&](const auto& c) {
                return (made.positions[k] - c).template head<2>().squaredNorm() <= r2;
            });
            if (!in) continue;
            out.positions.push_back(made.positions[k]);
            out.descriptors.push_back(made.descriptors[k]);
        }
        return out;
    }
    std::vector<std::uint32_t> indices;
    for (const Eigen::Vector3d& c : places) {
        for (std::uint32_t k : feature_indices_near(c, radius)) indices.push_back(k);
    }
    std::sort(indices.begin(), indices.end());
    indices.erase(std::unique(indices.begin(), indices.end()), indices.end());
    out.sample_spacing = features_.sample_spacing;
    out.positions.reserve(indices.size());
    out.descriptors.reserve(indices.size());
    for (std::uint32_t k : indices) {
        out.positions.push_back(features_.positions[k]);
        out.descriptors.push_back(features_.descriptors[k]);
    }
    return out;
}

std::vector<std::uint32_t> LocalisationMap::feature_indices_near(const Eigen::Vector3d& p,
                                                                 double radius) const {
    std::vector<std::uint32_t> out;
    const double r2 = radius * radius;
    for (std::size_t i = 0; i < features_.size(); ++i) {
        if ((features_.positions[i] - p).head<2>().squaredNorm() <= r2)
            out.push_back(std::uint32_t(i));
    }
    return out;
}

places::LocalFeatures LocalisationMap::features_near(const Eigen::Vector3d& p,
                                                     double radius) const {
    places::LocalFeatures out;
    out.sample_spacing = features_.sample_spacing;
    const double r2 = radius * radius;
    for (std::size_t i = 0; i < features_.size(); ++i) {
        if ((features_.positions[i] - p).head<2>().squaredNorm() > r2) continue;
        out.positions.push_back(features_.positions[i]);
        out.descriptors.push_back(features_.descriptors[i]);
    }
    return out;
}

void LocalisationMap::index_voxels(map::MergedVoxels merged) {
    voxels_ = std::move(merged.voxels);
    local_maps_ = merged.local_maps;
    sessions_ = merged.sessions;
    columns_ = std::make_shared<const VoxelColumns>(voxels_->voxels);
}

void LocalisationMap::place_keyframes(const map::MapData& map) {
    std::unordered_map<std::uint64_t, Eigen::Isometry3d> anchors;
    for (const map::PoseGraphNode& n : map.nodes) anchors[n.id] = n.T_world_anchor;
    index_ = places::RingKeyIndex(descriptor_config_.rings);
    std::vector<Eigen::Vector3f> local;
    for (const auto& stored : map.keyframes) {
        if (!stored) continue;
        const auto a = anchors.find(stored->node);
        if (a == anchors.end()) continue;
        MapKeyframe k;
        k.index = std::uint32_t(keyframes_.size());
        k.session = stored->session;
        k.node = stored->node;
        k.stamp = stored->data.stamp;
        k.T_map_lidar = a->second * stored->data.T_anchor_lidar;
        const places::ScanContext& d = stored->localisation_descriptor;
        if (!d.empty() && d.kind == descriptor_config_.kind &&
            d.rings == descriptor_config_.rings && d.sectors == descriptor_config_.sectors) {
            k.descriptor = d;
        } else {
            // No stored descriptor (format 1): the map's view from the keyframe's place.
            const Eigen::Isometry3d T_lidar_map = k.T_map_lidar.inverse();
            const Eigen::Matrix3f R = T_lidar_map.linear().cast<float>();
            const Eigen::Vector3f t = T_lidar_map.translation().cast<float>();
            local.clear();
            columns_->for_each_near(
                k.T_map_lidar.translation(), descriptor_config_.max_range,
                [&](std::uint32_t i) { local.push_back(R * voxels_->voxels[i].centre + t); });
            k.descriptor = places::make_scan_context(local, descriptor_config_);
            descriptors_computed_ = true;
        }
        if (!keyframes_.empty()) {
            path_length_ +=
                (k.T_map_lidar.translation() - keyframes_.back().T_map_lidar.translation())
                    .head<2>()
                    .norm();
        }
        index_.add(places::ring_key(k.descriptor), k.index);
        keyframes_.push_back(std::move(k));
    }
    if (keyframes_.empty()) {
        throw common::ConfigError("map",
                                  "no keyframe is placed in the graph: nothing to localise "
                                  "against");
    }
}

std::vector<places::RingKeyNeighbour> LocalisationMap::nearest_keyframes(
    const places::ScanContext& query, std::size_t k) const {
    if (query.empty() || query.rings != descriptor_config_.rings) return {};
    return index_.nearest(places::ring_key(query), k);
}

std::vector<std::uint32_t> LocalisationMap::keyframes_near(const Eigen::Vector3d& p,
                                                           double radius) const {
    std::vector<std::uint32_t> out;
    const double r2 = radius * radius;
    for (const MapKeyframe& k : keyframes_) {
        if ((k.T_map_lidar.translation() - p).head<2>().squaredNorm() <= r2) out.push_back(k.index);
    }
    return out;
}

std::vector<Eigen::Vector3f> LocalisationMap::centres_near(const Eigen::Vector3d& p,
                                                           double radius) const {
    if (!columns_) throw common::ConfigError("map", "is paged: its voxels are on disk");
    return columns_->centres_near(p, radius);
}

bool LocalisationMap::covers(const Eigen::Vector3d& p, double radius) const {
    if (!columns_) {
        // Any cell holding a voxel whose square reaches within radius of p.
        const int reach = int(std::ceil(radius / kCoverageCell)) + 1;
        const auto cx = std::int64_t(std::floor(p.x() / kCoverageCell));
        const auto cy = std::int64_t(std::floor(p.y() / kCoverageCell));
        const double r2 = radius * radius;
        for (int dx = -reach; dx <= reach; ++dx) {
            for (int dy = -reach; dy <= reach; ++dy) {
                const double x0 = double(cx + dx) * kCoverageCell;
                const double y0 = double(cy + dy) * kCoverageCell;
                const double ex = std::max({x0 - p.x(), 0.0, p.x() - (x0 + kCoverageCell)});
                const double ey = std::max({y0 - p.y(), 0.0, p.y() - (y0 + kCoverageCell)});
                if (ex * ex + ey * ey > r2) continue;
                if (coverage_.count(
                        coverage_key(x0 + 0.5 * kCoverageCell, y0 + 0.5 * kCoverageCell)))
                    return true;
            }
        }
        return false;
    }
    bool any = false;
    columns_->for_each_near(p, radius, [&](std::uint32_t) { any = true; });
    return any;
}

std::shared_ptr<const LocalisationMap> load_localisation_map(const std::string& dir,
                                                             const LocalisationMapConfig& config,
                                                             std::vector<std::string>* refused,
                                                             double page_radius,
                                                             double page_above_mb) {
    // The graph and keyframes; the local maps are read one at a time (never all at once).
    const map::LoadedMap skeleton = map::load_map(dir, false);
    std::uint64_t bytes = 0;
    for (const map::ManifestEntry& e : skeleton.local_map_files) bytes += e.size;
    const bool paging = page_radius > 0.0 && double(bytes) > page_above_mb * 1e6;
    std::vector<std::string> failed = skeleton.refused;
    try {
        auto map = std::make_shared<const LocalisationMap>(
            skeleton.map, config, std::make_shared<const MapPages>(dir, skeleton, config),
            paging ? page_radius : 0.0, &failed);
        if (refused) *refused = failed;
        return map;
    } catch (const common::ConfigError& e) {
        throw common::ConfigError(dir, e.problem());
    }
}

}  // namespace ltm::localisation
