#pragma once
// The localisation map paged (issue 28 item 3): the local maps of a map directory stay on disk and
// only those anchored within a radius of a point are read (one file at a time, checked as load_map
// checks them) and merged into a neighbourhood: the voxels, registration target and column index
// that tracking registers to, built as LocalisationMap builds them for the whole map
// (map::merge_voxels with the same filter, make_registration_target with the same grids).
//
// A local map is chosen by its anchor's horizontal distance to the centre (from the graph, no
// voxel read): radius must exceed the local maps' reach for the neighbourhood to hold every voxel
// of the whole map within (radius - reach) of the centre. A neighbourhood whose radius holds every
// local map is the whole map, voxel for voxel.
#include <Eigen/Geometry>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <unordered_set>
#include <vector>

#include "common/core/local_map_data.hpp"
#include "localisation/core/localisation_map.hpp"
#include "map/core/map_store.hpp"
#include "map/core/merged_voxels.hpp"
#include "registration/core/registration_target.hpp"

namespace ltm::localisation {

// The merged voxels of the local maps anchored within `radius` of `centre`.
struct Neighbourhood {
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    double radius = 0.0;
    std::vector<std::uint64_t> nodes;  // the local maps held (their graph nodes), ascending
    bool complete = false;             // every local map of the map is held
    std::shared_ptr<const common::LocalMapData> voxels;  // map frame, as LocalisationMap::voxels
    std::shared_ptr<const registration::RegistrationTarget> target;
    std::size_t voxel_count() const { return voxels ? voxels->voxels.size() : 0; }
    std::size_t memory_bytes() const;  // its voxels and grids
    EIGEN_MAKE_ALIGNED_OPERATOR_NEW
};

class MapPages {
  public:
    // Reads the manifest, graph and keyframes of `dir` (map::load_map without the local maps).
    // Throws as load_map does, with one line.
    MapPages(std::string dir, const LocalisationMapConfig& config = {});
    // The same from a load_map(dir, false) of it already made.
    MapPages(std::string dir, const map::LoadedMap& skeleton, const LocalisationMapConfig& config);

    // The neighbourhood of `centre` (horizontal distance of the anchors <= radius). Reads the
    // local maps it needs; a damaged one is left out and named in *refused. Safe to call from
    // another thread than the one using earlier neighbourhoods (they are immutable).
    std::shared_ptr<const Neighbourhood> build(const Eigen::Vector3d& centre, double radius,
                                               std::vector<std::string>* refused = nullptr) const;
    // The local maps anchored within `radius` of any of `centres` (a global query's initial
    // poses), merged as one neighbourhood (its centre: the first).
    std::shared_ptr<const Neighbourhood> build(const std::vector<Eigen::Vector3d>& centres,
                                               double radius,
                                               std::vector<std::string>* refused = nullptr) const;

    // Every local map merged (as map::merge_voxels merges a whole map), read one at a time; a
    // damaged one is left out and named in *refused.
    map::MergedVoxels merge_all(std::vector<std::string>* refused = nullptr) const;
    // Every voxel a merge would consider (map::merges), in the map frame, a local map at a time
    // (never all in memory): f(centre, voxel_size of its local map). Damaged maps as above.
    void for_each_voxel(const std::function<void(const Eigen::Vector3f&, float)>& f,
                        std::vector<std::string>* refused = nullptr) const;

    // The local maps anchored within `radius` of `centre` (graph nodes, ascending).
    std::vector<std::uint64_t> nodes_near(const Eigen::Vector3d& centre, double radius) const;
    std::vector<std::uint64_t> nodes_near(const std::vector<Eigen::Vector3d>& centres,
                                          double radius) const;
    std::size_t local_maps() const { return files_.size(); }
    const std::string& dir() const { return dir_; }

  private:
    // The local maps for which `take` says yes, merged; their nodes in *nodes.
    template <class Take>
    map::MergedVoxels merge(Take&& take, std::vector<std::uint64_t>* nodes,
                            std::vector<std::string>* refused) const;

    struct File {
        map::ManifestEntry entry;
        Eigen::Isometry3d T_world_anchor = Eigen::Isometry3d::Identity();  // the graph's
        Eigen::Vector3d anchor = Eigen::Vector3d::Zero();                  // map frame
        EIGEN_MAKE_ALIGNED_OPERATOR_NEW
    };
    std::string dir_;
    LocalisationMapConfig config_;
    std::uint32_t format_version_ = 0;
    std::unordered_set<std::uint64_t> graph_nodes_;
    // Placed in the graph, by node (the graph's poses are all that is kept of it: the keyframes
    // are the LocalisationMap's).
    std::vector<File, Eigen::aligned_allocator<File>> files_;
};

}  // namespace ltm::localisation
