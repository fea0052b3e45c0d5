#pragma once
// A saved ltm map made ready for localisation (METHOD.md section 6): every keyframe placed in the
// map frame with its ScanContext++ descriptor and a ring-key index over all of them, and the
// voxels of every local map merged into one voxel map in the map frame (centre + normal per voxel,
// the healthy ones only), which global localisation verifies against and tracking registers to.
//
// Local maps overlap: where several have a voxel in the same map-frame cell, the one of the local
// map anchored nearest to it is kept (map::merge_voxels). Maps of format 1 carry no ScanContext++
// descriptors: they are computed on load from the merged voxel centres within the descriptor's
// range of each keyframe (a rendered view of the map, not the keyframe's own scan: retrieval is
// weaker on such maps).
//
// Paged (issue 28 item 3; made with a MapPages and a radius): the whole map is never merged. What
// stays is the site's index: the keyframes with their descriptors and a coverage grid (2 m cells
// that hold a voxel, for covers()). Tracking registers to a neighbourhood of the pose
// (neighbourhood_builder.hpp); a global query reads the local maps within the radius of its
// places (neighbourhood_around) and makes their local features (features_near_places).
#include <Eigen/Geometry>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <unordered_set>
#include <vector>

#include "common/core/local_map_data.hpp"
#include "map/core/map_data.hpp"
#include "map/core/merged_voxels.hpp"
#include "places/core/local_features.hpp"
#include "places/core/ring_key_index.hpp"
#include "places/core/scan_context.hpp"
#include "registration/core/registration_target.hpp"

namespace ltm::localisation {

struct LocalisationMapConfig {
    double min_health = 0.0;     // voxels below this health are left out [0..1]
    double min_planarity = 0.4;  // voxels below this planarity are left out (no usable plane)
    int coarse_factor = 3;       // coarse registration grid [voxels] (0: none)
    // The ScanContext++ settings used for a map that has no stored descriptors (format 1); a map
    // with descriptors keeps its own (the query must be described the same way).
    places::ScanContextConfig descriptor = default_descriptor();
    // Local features (ground samples with a local ScanContext++ each) of the whole map, computed
    // once on load on a grid of feature_cell; a query's features use the same settings.
    bool local_features = true;
    places::LocalFeatureConfig features;
    double feature_cell = 24.0;  // [m]

    static places::ScanContextConfig default_descriptor() {
        places::ScanContextConfig c;
        c.kind = places::ScanContextKind::kMeanVariance;
        return c;
    }
};

struct MapKeyframe {
    std::uint32_t index = 0;  // in the map's keyframe order
    std::uint32_t session = 0;
    std::uint64_t node = 0;
    double stamp = 0.0;
    Eigen::Isometry3d T_map_lidar = Eigen::Isometry3d::Identity();
    places::ScanContext descriptor;  // ScanContext++ (kMeanVariance)
    EIGEN_MAKE_ALIGNED_OPERATOR_NEW
};

class MapPages;
class VoxelColumns;
struct Neighbourhood;

class LocalisationMap {
  public:
    // Throws common::ConfigError when the map holds nothing to localise against (no keyframe or
    // no voxel), with one line saying so. With `pages` (the same map directory, opened paged) and
    // page_radius > 0 the map is paged once loaded (above).
    // With pages, `map` need not hold its local maps: they are read from pages (a damaged one is
    // left out and named in *refused); the map is paged when page_radius > 0.
    LocalisationMap(const map::MapData& map, const LocalisationMapConfig& config = {},
                    std::shared_ptr<const MapPages> pages = nullptr, double page_radius = 0.0,
                    std::vector<std::string>* refused = nullptr);
    ~LocalisationMap();

    const places::ScanContextConfig& descriptor_config() const { return descriptor_config_; }
    bool descriptors_computed() const { return descriptors_computed_; }  // format-1 map
    const std::vector<MapKeyframe, Eigen::aligned_allocator<MapKeyframe>>& keyframes() const {
        return keyframes_;
    }
    // The ring-key neighbours of a query descriptor (nearest first), as keyframe indices.
    std::vector<places::RingKeyNeighbour> nearest_keyframes(const places::ScanContext& query,
                                                            std::size_t k) const;
    // Keyframes whose position is within `radius` of p (horizontal distance), any order.
    std::vector<std::uint32_t> keyframes_near(const Eigen::Vector3d& p, double radius) const;

    bool paged() const { return pages_ != nullptr; }
    double page_radius() const { return page_radius_; }
    const std::shared_ptr<const MapPages>& pages() const { return pages_; }
    // Every usable voxel of the map in the map frame (grid frame = map frame, T_anchor_grid = I).
    // Not paged only (common::ConfigError, one line, on a paged map).
    const common::LocalMapData& voxels() const;
    // The merged voxels as registration grids (fine and coarse), in the map frame. Not paged only.
    const registration::RegistrationTarget& target() const;
    // What a global query around these map-frame positions verifies against: the whole map's
    // target, or (paged) the local maps anchored within page_radius of any of them, merged (the
    // last one is kept and given again while it holds every local map asked for). Thread-safe.
    // Throws common::IoError when no local map can be read.
    std::shared_ptr<const registration::RegistrationTarget> target_around(
        const std::vector<Eigen::Vector3d>& positions) const;
    // Paged: the same as a neighbourhood (its local maps, voxels and target); null when not
    // paged. A neighbourhood still held elsewhere that has every local map asked for is given
    // again; none is kept here (a query's map lives as long as the query, or the tracking that
    // adopts it).
    std::shared_ptr<const Neighbourhood> neighbourhood_around(
        const std::vector<Eigen::Vector3d>& positions) const;
    // The voxel centres within `radius` (horizontal) of p, in the map frame. Not paged only.
    std::vector<Eigen::Vector3f> centres_near(const Eigen::Vector3d& p, double radius) const;
    // The map's local features within `radius` (horizontal) of p (empty without local features).
    places::LocalFeatures features_near(const Eigen::Vector3d& p, double radius) const;
    std::vector<std::uint32_t> feature_indices_near(const Eigen::Vector3d& p, double radius) const;
    // ... within `radius` of any of `places`, each once: the whole map's (in their order on
    // load), or (paged) made from the voxels of `around`, the local maps a query read there
    // (empty without local features or without `around`).
    places::LocalFeatures features_near_places(const std::vector<Eigen::Vector3d>& places,
                                               double radius, const Neighbourhood* around) const;
    const places::LocalFeatures& features() const { return features_; }
    const places::LocalFeatureConfig& feature_config() const { return feature_config_; }
    // Whether the map has local features: made on load, or (paged) by a query from the local
    // maps it reads (features_near_places).
    bool has_features() const { return feature_map_config_.local_features; }
    // Paged: the features of the cells within `near` of `places`, from a neighbourhood's voxels.
    places::LocalFeatures features_around(const Neighbourhood& n,
                                          const std::vector<Eigen::Vector3d>& places,
                                          double near) const;
    std::size_t feature_count() const { return features_.size(); }

    // Whether any map voxel is within `radius` (horizontal) of p.
    bool covers(const Eigen::Vector3d& p, double radius) const;

    double voxel_size() const { return voxel_size_; }
    double coarse_voxel_size() const { return coarse_voxel_size_; }  // = voxel_size(): no coarse
    // Merged voxels (whole); paged (never merged whole): the local maps' voxels summed.
    std::size_t voxel_count() const { return voxel_count_; }
    std::size_t local_maps() const { return local_maps_; }
    std::size_t sessions() const { return sessions_; }
    // Horizontal extent of the keyframe path [m] (sum of distances between consecutive ones).
    double path_length() const { return path_length_; }
    // What it holds (bytes): keyframes and their descriptors, the whole map's voxels and grids,
    // the local features, the coverage cells; not the neighbourhoods a paged map gives out.
    std::size_t memory_bytes() const;

  private:
    void index_voxels(map::MergedVoxels merged);
    void place_keyframes(const map::MapData& map);
    void index_coverage();
    std::uint64_t coverage_key(double x, double y) const;

    places::ScanContextConfig descriptor_config_;
    bool descriptors_computed_ = false;
    std::vector<MapKeyframe, Eigen::aligned_allocator<MapKeyframe>> keyframes_;
    places::RingKeyIndex index_;
    std::shared_ptr<common::LocalMapData> voxels_;
    std::shared_ptr<const VoxelColumns> columns_;  // of voxels_ (whole only)
    std::shared_ptr<const registration::RegistrationTarget> target_;
    places::LocalFeatureConfig feature_config_;
    LocalisationMapConfig feature_map_config_;  // how the features are made (map_features.hpp)
    places::LocalFeatures features_;            // every sample of the map, map frame (paged: none)
    std::size_t local_maps_ = 0, sessions_ = 0;
    double path_length_ = 0.0;
    double voxel_size_ = 0.0, coarse_voxel_size_ = 0.0;
    std::size_t voxel_count_ = 0;
    // Paged: the map directory, the query radius, the cells holding a voxel, the last query's.
    std::shared_ptr<const MapPages> pages_;
    double page_radius_ = 0.0;
    std::unordered_set<std::uint64_t> coverage_;
    mutable std::mutex around_mutex_;
    mutable std::weak_ptr<const Neighbourhood> around_;
};

// Loads a map directory (map::load_map) for localisation. Throws common::IoError /
// map::MapFormatError / common::ConfigError with one line when it cannot be used; files the
// loader refused (a damaged local map) are reported in *refused and the rest is used.
// The local maps are read one at a time. With page_radius > 0 the map is paged (above) when its
// local-map files hold more than page_above_mb [MB] (0: always); else it is held whole.
std::shared_ptr<const LocalisationMap> load_localisation_map(
    const std::string& dir, const LocalisationMapConfig& config = {},
    std::vector<std::string>* refused = nullptr, double page_radius = 0.0,
    double page_above_mb = 0.0);

}  // namespace ltm::localisation
