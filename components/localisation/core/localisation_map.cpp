#include "localisation/core/localisation_map.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "common/core/config_check.hpp"
#include "mapping/core/map_store.hpp"

namespace ltm::localisation {

namespace {

constexpr double kColumnSize = 8.0;  // [m] cell of the 2-D index of voxel centres

std::uint64_t column_key(double x, double y) {
    const auto cx = std::int64_t(std::floor(x / kColumnSize));
    const auto cy = std::int64_t(std::floor(y / kColumnSize));
    return (std::uint64_t(cx + (1 << 30)) << 32) | std::uint64_t(cy + (1 << 30));
}

// A lattice point's cell of a grid of `step` (the point is at a multiple of step, or anywhere).
std::uint64_t lattice_key(double x, double y, double step) {
    const auto ix = std::int64_t(std::lround(x / step)), iy = std::int64_t(std::lround(y / step));
    return (std::uint64_t(ix + (1 << 30)) << 32) | std::uint64_t(iy + (1 << 30));
}

bool usable(const common::VoxelData& v, const LocalisationMapConfig& config) {
    return v.point_count > 0 && v.planarity >= config.min_planarity &&
           v.life.health >= config.min_health && std::abs(v.normal.squaredNorm() - 1.0f) < 1e-3f &&
           v.centre.allFinite();
}

}  // namespace

struct LocalisationMap::Columns {
    std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> cells;  // voxel indices

    template <class F>
    void for_each_near(const std::vector<common::VoxelData>& voxels, const Eigen::Vector3d& p,
                       double radius, F&& f) const {
        const double r2 = radius * radius;
        const int reach = int(std::ceil(radius / kColumnSize));
        const double x0 = p.x(), y0 = p.y();
        for (int dx = -reach; dx <= reach; ++dx) {
            for (int dy = -reach; dy <= reach; ++dy) {
                const auto it =
                    cells.find(column_key(x0 + dx * kColumnSize, y0 + dy * kColumnSize));
                if (it == cells.end()) continue;
                for (std::uint32_t i : it->second) {
                    const Eigen::Vector3f& c = voxels[i].centre;
                    const double ex = c.x() - x0, ey = c.y() - y0;
                    if (ex * ex + ey * ey <= r2) f(i);
                }
            }
        }
    }
};

LocalisationMap::LocalisationMap(const mapping::MapData& map, const LocalisationMapConfig& config)
    : index_(1) {
    if (map.keyframes.empty()) {
        throw common::ConfigError("map", "has no keyframes: nothing to localise against");
    }
    merge_voxels(map, config);
    if (voxels_->voxels.empty()) {
        throw common::ConfigError("map", "has no usable voxels: nothing to register against");
    }
    const bool stored =
        map.localisation_descriptor_config.rings > 0 &&
        map.localisation_descriptor_config.kind == mapping::ScanContextKind::kMeanVariance;
    target_ = std::make_shared<const mapping::RegistrationTarget>(
        mapping::make_registration_target(*voxels_, config.min_planarity, config.coarse_factor));
    descriptor_config_ = stored ? map.localisation_descriptor_config : config.descriptor;
    place_keyframes(map);
    feature_config_ = config.features;
    if (config.local_features) make_features(config);
}

void LocalisationMap::make_features(const LocalisationMapConfig& config) {
    // Samples lie on a lattice anchored at the frame's origin: a sample found from two cells is
    // the same sample (same lattice point), kept once.
    std::unordered_map<std::uint64_t, bool> seen;
    const double cell = config.feature_cell;
    const double half_diagonal = cell * 0.7072;
    std::unordered_map<std::uint64_t, Eigen::Vector2d> cells;
    for (const common::VoxelData& v : voxels_->voxels) {
        const double cx = (std::floor(v.centre.x() / cell) + 0.5) * cell;
        const double cy = (std::floor(v.centre.y() / cell) + 0.5) * cell;
        cells.emplace(lattice_key(cx, cy, cell), Eigen::Vector2d(cx, cy));
    }
    const double spacing = config.features.sample_spacing;
    features_.sample_spacing = spacing;
    // Every lattice point of a tile (a thinned lattice would break the matches' refinement).
    LocalFeatureConfig tile = config.features;
    tile.max_samples = std::max(tile.max_samples, int(std::pow(cell / spacing + 2.0, 2.0)) * 2);
    for (const auto& [key, c] : cells) {
        const Eigen::Vector3d centre(c.x(), c.y(), 0.0);
        const LocalFeatures f =
            make_local_features(centres_near(centre, half_diagonal + config.features.radius), tile,
                                centre, half_diagonal);
        for (std::size_t i = 0; i < f.size(); ++i) {
            const Eigen::Vector3d& p = f.positions[i];
            if (std::abs(p.x() - c.x()) > 0.5 * cell || std::abs(p.y() - c.y()) > 0.5 * cell)
                continue;  // another cell's sample
            const std::uint64_t id = lattice_key(p.x(), p.y(), spacing);
            if (!seen.emplace(id, true).second) continue;
            features_.positions.push_back(p);
            features_.descriptors.push_back(f.descriptors[i]);
        }
    }
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

LocalFeatures LocalisationMap::features_near(const Eigen::Vector3d& p, double radius) const {
    LocalFeatures out;
    out.sample_spacing = features_.sample_spacing;
    const double r2 = radius * radius;
    for (std::size_t i = 0; i < features_.size(); ++i) {
        if ((features_.positions[i] - p).head<2>().squaredNorm() > r2) continue;
        out.positions.push_back(features_.positions[i]);
        out.descriptors.push_back(features_.descriptors[i]);
    }
    return out;
}

void LocalisationMap::merge_voxels(const mapping::MapData& map,
                                   const LocalisationMapConfig& config) {
    std::unordered_map<std::uint64_t, Eigen::Isometry3d> anchors;
    for (const mapping::PoseGraphNode& n : map.nodes) anchors[n.id] = n.T_world_anchor;
    voxels_ = std::make_shared<common::LocalMapData>();
    float voxel_size = 0.0f;
    for (const mapping::StoredLocalMap& lm : map.local_maps) {
        if (lm.data && anchors.count(lm.node)) {
            voxel_size = std::max(voxel_size, lm.data->voxel_size);
        }
    }
    if (!(voxel_size > 0.0f)) voxel_size = 1.0f;
    voxels_->voxel_size = voxel_size;
    voxels_->finished = true;
    const float inv = 1.0f / voxel_size;
    std::unordered_map<std::uint64_t, std::uint32_t> slot;  // packed cell -> voxel index
    // Where local maps overlap, a cell takes the voxel of the local map anchored nearest to it
    // (built while the sensor was closest): neighbouring cells then come from the same local map,
    // whose surfaces agree with each other. Taking the voxel with the most points instead made a
    // patchwork of local maps a few centimetres apart (a loop-closed map fitted its own scans
    // with 85 % of the structure within 0.3 m, against 99 % for a map from the true poses).
    std::vector<float> anchor_distance;  // per merged voxel
    std::vector<std::uint32_t> sessions;
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = -lo;
    for (const mapping::StoredLocalMap& lm : map.local_maps) {
        const auto a = anchors.find(lm.node);
        if (!lm.data || a == anchors.end()) continue;
        ++local_maps_;
        if (std::find(sessions.begin(), sessions.end(), lm.session) == sessions.end()) {
            sessions.push_back(lm.session);
        }
        const Eigen::Isometry3d T = a->second * lm.data->T_anchor_grid;
        const Eigen::Matrix3f R = T.linear().cast<float>();
        const Eigen::Vector3f t = T.translation().cast<float>();
        const Eigen::Vector3f anchor = a->second.translation().cast<float>();
        for (const common::VoxelData& v : lm.data->voxels) {
            if (!usable(v, config)) continue;
            common::VoxelData w = v;
            w.centre = R * v.centre + t;
            w.normal = (R * v.normal).normalized();
            const Eigen::Vector3f cell = (w.centre * inv).array().floor();
            if (!(cell.cwiseAbs().maxCoeff() < float((1 << 20) - 1))) continue;
            w.index = cell.cast<int>();
            w.life.seen.clear();
            w.stability *= std::clamp(w.life.health, 0.0f, 1.0f);  // established voxels weigh more
            const std::uint64_t key = (std::uint64_t(w.index.x() + (1 << 20)) << 42) |
                                      (std::uint64_t(w.index.y() + (1 << 20)) << 21) |
                                      std::uint64_t(w.index.z() + (1 << 20));
            const float d = (w.centre - anchor).head<2>().norm();
            const auto [it, fresh] = slot.emplace(key, std::uint32_t(voxels_->voxels.size()));
            if (fresh) {
                voxels_->voxels.push_back(std::move(w));
                anchor_distance.push_back(d);
                lo = lo.cwiseMin(voxels_->voxels.back().centre.cast<double>());
                hi = hi.cwiseMax(voxels_->voxels.back().centre.cast<double>());
            } else if (d < anchor_distance[it->second]) {
                voxels_->voxels[it->second] = std::move(w);
                anchor_distance[it->second] = d;
            }
        }
    }
    sessions_ = sessions.size();
    if (!voxels_->voxels.empty()) {
        voxels_->bbox_min = lo;
        voxels_->bbox_max = hi;
    }
    auto columns = std::make_shared<Columns>();
    for (std::uint32_t i = 0; i < voxels_->voxels.size(); ++i) {
        const Eigen::Vector3f& c = voxels_->voxels[i].centre;
        columns->cells[column_key(c.x(), c.y())].push_back(i);
    }
    columns_ = std::move(columns);
}

void LocalisationMap::place_keyframes(const mapping::MapData& map) {
    std::unordered_map<std::uint64_t, Eigen::Isometry3d> anchors;
    for (const mapping::PoseGraphNode& n : map.nodes) anchors[n.id] = n.T_world_anchor;
    index_ = mapping::RingKeyIndex(descriptor_config_.rings);
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
        const mapping::ScanContext& d = stored->localisation_descriptor;
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
                voxels_->voxels, k.T_map_lidar.translation(), descriptor_config_.max_range,
                [&](std::uint32_t i) { local.push_back(R * voxels_->voxels[i].centre + t); });
            k.descriptor = mapping::make_scan_context(local, descriptor_config_);
            descriptors_computed_ = true;
        }
        if (!keyframes_.empty()) {
            path_length_ +=
                (k.T_map_lidar.translation() - keyframes_.back().T_map_lidar.translation())
                    .head<2>()
                    .norm();
        }
        index_.add(mapping::ring_key(k.descriptor), k.index);
        keyframes_.push_back(std::move(k));
    }
    if (keyframes_.empty()) {
        throw common::ConfigError("map",
                                  "no keyframe is placed in the graph: nothing to localise "
                                  "against");
    }
}

std::vector<mapping::RingKeyNeighbour> LocalisationMap::nearest_keyframes(
    const mapping::ScanContext& query, std::size_t k) const {
    if (query.empty() || query.rings != descriptor_config_.rings) return {};
    return index_.nearest(mapping::ring_key(query), k);
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
    std::vector<Eigen::Vector3f> out;
    columns_->for_each_near(voxels_->voxels, p, radius,
                            [&](std::uint32_t i) { out.push_back(voxels_->voxels[i].centre); });
    return out;
}

bool LocalisationMap::covers(const Eigen::Vector3d& p, double radius) const {
    bool any = false;
    columns_->for_each_near(voxels_->voxels, p, radius, [&](std::uint32_t) { any = true; });
    return any;
}

std::shared_ptr<const LocalisationMap> load_localisation_map(const std::string& dir,
                                                             const LocalisationMapConfig& config,
                                                             std::vector<std::string>* refused) {
    mapping::LoadedMap loaded = mapping::load_map(dir);
    if (refused) *refused = loaded.refused;
    try {
        return std::make_shared<const LocalisationMap>(loaded.map, config);
    } catch (const common::ConfigError& e) {
        throw common::ConfigError(dir, e.problem());
    }
}

}  // namespace ltm::localisation
