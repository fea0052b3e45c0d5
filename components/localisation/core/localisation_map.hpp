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
#include <Eigen/Geometry>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/core/local_map_data.hpp"
#include "map/core/map_data.hpp"
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

class LocalisationMap {
  public:
    // Throws common::ConfigError when the map holds nothing to localise against (no keyframe or
    // no voxel), with one line saying so.
    LocalisationMap(const map::MapData& map, const LocalisationMapConfig& config = {});

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

    // Every usable voxel of the map in the map frame (grid frame = map frame, T_anchor_grid = I).
    const common::LocalMapData& voxels() const { return *voxels_; }
    std::shared_ptr<const common::LocalMapData> voxels_ptr() const { return voxels_; }
    // The merged voxels as registration grids (fine and coarse), in the map frame.
    const registration::RegistrationTarget& target() const { return *target_; }
    // The voxel centres within `radius` (horizontal) of p, in the map frame.
    std::vector<Eigen::Vector3f> centres_near(const Eigen::Vector3d& p, double radius) const;
    // The map's local features within `radius` (horizontal) of p (empty without local features).
    places::LocalFeatures features_near(const Eigen::Vector3d& p, double radius) const;
    std::vector<std::uint32_t> feature_indices_near(const Eigen::Vector3d& p, double radius) const;
    const places::LocalFeatures& features() const { return features_; }
    const places::LocalFeatureConfig& feature_config() const { return feature_config_; }
    std::size_t feature_count() const { return features_.size(); }

    // Whether any map voxel is within `radius` (horizontal) of p.
    bool covers(const Eigen::Vector3d& p, double radius) const;

    double voxel_size() const { return voxels_->voxel_size; }
    std::size_t local_maps() const { return local_maps_; }
    std::size_t sessions() const { return sessions_; }
    // Horizontal extent of the keyframe path [m] (sum of distances between consecutive ones).
    double path_length() const { return path_length_; }

  private:
    struct Columns;  // 2-D grid of voxel centres for range queries
    void index_voxels(const map::MapData& map, const LocalisationMapConfig& config);
    void place_keyframes(const map::MapData& map);
    void make_features(const LocalisationMapConfig& config);

    places::ScanContextConfig descriptor_config_;
    bool descriptors_computed_ = false;
    std::vector<MapKeyframe, Eigen::aligned_allocator<MapKeyframe>> keyframes_;
    places::RingKeyIndex index_;
    std::shared_ptr<common::LocalMapData> voxels_;
    std::shared_ptr<const Columns> columns_;
    std::shared_ptr<const registration::RegistrationTarget> target_;
    places::LocalFeatureConfig feature_config_;
    places::LocalFeatures features_;  // every sample of the map, map frame
    std::size_t local_maps_ = 0, sessions_ = 0;
    double path_length_ = 0.0;
};

// Loads a map directory (map::load_map) for localisation. Throws common::IoError /
// map::MapFormatError / common::ConfigError with one line when it cannot be used; files the
// loader refused (a damaged local map) are reported in *refused and the rest is used.
std::shared_ptr<const LocalisationMap> load_localisation_map(
    const std::string& dir, const LocalisationMapConfig& config = {},
    std::vector<std::string>* refused = nullptr);

}  // namespace ltm::localisation
