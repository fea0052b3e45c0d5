#pragma once
// Builds the neighbourhoods of a paged map (map_pages.hpp) on a thread of its own, so that the
// tracking thread never waits for the disk or a merge: it asks for the neighbourhood of its pose
// when it has moved far enough from the current one's centre (request, returns at once), keeps
// registering to the current one while the build runs, and swaps the new one in between scans
// (take, returns at once). A request made while a build runs replaces any request still waiting:
// only the latest pose is built.
#include <Eigen/Geometry>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "localisation/core/map_pages.hpp"

namespace ltm::localisation {

// The localisation component's paging on a site (its versions never change once written) when
// the launch config gives none (localisation README, "The map paged"): a map whose local-map files
// hold more than 100 MB (about three times site_loop's 1.1 km, ~260 MiB merged in memory) is
// paged with a radius of 100 m (site_loop's day 1 tracks within 5 mm of the whole map there); a
// smaller one is held whole (a paged global query reads its local maps from disk: 0.1 -> 0.6 s
// on site_loop, where nothing would be saved).
constexpr double kSiteNeighbourhoodRadius = 100.0;  // [m]
constexpr double kSitePageAboveMb = 100.0;          // [MB]

struct NeighbourhoodConfig {
    // Local maps anchored within this (horizontal) of the pose are held for tracking, and within
    // this of a global query's initial poses for its verification [m]; 0: no paging, the whole
    // map's voxels in memory (the default of the core and of a `map` directory; on a site the
    // component pages with kSiteNeighbourhoodRadius).
    double radius = 0.0;
    // A new neighbourhood is asked for when the pose is this far (horizontal) from the current
    // one's centre [m]; below radius, so that the pose stays well inside what is held.
    double rebuild_distance = 40.0;
    // ... only when the map's local-map files hold more than this [MB]; a smaller map is held
    // whole (0: paged whenever radius > 0).
    double page_above_mb = 0.0;
};

// Throws common::ConfigError (one line) when a value is out of range.
void validate(const NeighbourhoodConfig& config);

class NeighbourhoodBuilder {
  public:
    // Builds the first neighbourhood around `start` before returning (nothing to track against
    // before it).
    NeighbourhoodBuilder(std::shared_ptr<const MapPages> pages, const NeighbourhoodConfig& config,
                         const Eigen::Vector3d& start);
    ~NeighbourhoodBuilder();
    NeighbourhoodBuilder(const NeighbourhoodBuilder&) = delete;
    NeighbourhoodBuilder& operator=(const NeighbourhoodBuilder&) = delete;

    // The neighbourhood in use (never null).
    const std::shared_ptr<const Neighbourhood>& current() const { return current_; }
    // Called by the tracking thread with its pose after each scan: swaps in a finished build
    // (true when it did) and asks for a new one when the pose has moved rebuild_distance from the
    // current (or pending) centre. Never waits for a build.
    bool update(const Eigen::Vector3d& pose);
    // Whether the neighbourhood in use holds the map around p: the whole map, or p within
    // radius - rebuild_distance of its centre (after a relocalisation elsewhere it does not until
    // the build asked for arrives).
    bool holds(const Eigen::Vector3d& p) const;
    // A neighbourhood built elsewhere (a global query's, around its answer at `pose`) in use from
    // now when the one in use does not hold `pose` and it has every local map within radius of
    // `pose`: tracking goes on there at once instead of waiting for a build (true when taken).
    bool adopt(const std::shared_ptr<const Neighbourhood>& n, const Eigen::Vector3d& pose);
    // Waits until no build is pending or running (tests and benches that must be reproducible;
    // never on the tracking thread), then swaps in the last one.
    void settle();

    std::size_t builds() const;                // finished builds, the first included
    std::vector<std::string> refused() const;  // damaged local maps met so far, one line each

  private:
    void run();
    bool holds_locked(const Eigen::Vector3d& p) const;
    // A finished build is swapped in when it is nearer the latest pose asked for than the one in
    // use (a build asked for before an adoption elsewhere is not).
    void take_ready();

    std::shared_ptr<const MapPages> pages_;
    NeighbourhoodConfig config_;
    std::shared_ptr<const Neighbourhood> current_;
    Eigen::Vector3d asked_ = Eigen::Vector3d::Zero();  // centre of the latest request
    mutable std::mutex mutex_;
    std::condition_variable wake_, idle_;
    std::optional<Eigen::Vector3d> request_;  // waiting for the thread
    bool busy_ = false, stop_ = false;
    std::shared_ptr<const Neighbourhood> ready_;  // built, not yet swapped in
    std::size_t builds_ = 0;
    std::vector<std::string> refused_;
    std::thread thread_;
};

}  // namespace ltm::localisation
