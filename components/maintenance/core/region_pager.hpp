#pragma once
// Regions of the maintained map kept on disk while the robot is away from them (issue 28 item 3:
// what stays in memory is the neighbourhood the robot needs). A paged-out region is one file in
// the pager's folder, `region_X_Y.bin`: the region's checksummed section as in the map file
// (region_io.hpp). page_in() reads it back (and removes the file); the voxels come back exactly
// as they left (same order, same state), so a pass or a view over a region that was paged out and
// in decides as over one that never left.
//
// The folder is the pager's scratch space for one run: files of an earlier run in it are removed
// at construction, and the pager's own ones when it is destroyed (the maintained map itself is
// saved with LongTermMap::save, which copies the paged regions' sections into the map file).
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "maintenance/core/maintenance_config.hpp"
#include "maintenance/core/observation_map.hpp"

namespace ltm::maintenance {

using RegionKey = std::pair<int, int>;

// Which regions stay in memory (LongTermMap::set_paging; keys of the maintenance component).
struct PagingConfig {
    // [m] a region whose square is farther than this from the latest scan's sensor goes to disk,
    // unless a view judged it since the last pass (the pass needs it); a region a scan's points or
    // a view reach comes back. 0: every region stays in memory. Best at least max_range plus the
    // distance driven in view_delay (a view judges up to max_range around where it was taken,
    // view_delay later), or regions go out and come back.
    double radius = 0.0;
    std::string dir;  // the paged-out regions' folder (scratch; required when radius > 0)
};

class RegionPager {
  public:
    // Creates `dir` when missing. Throws common::IoError when it cannot be made or written.
    RegionPager(std::string dir, const MaintenanceConfig& config);
    ~RegionPager();
    RegionPager(const RegionPager&) = delete;
    RegionPager& operator=(const RegionPager&) = delete;

    // Writes the region to its file (the map can then be dropped). Throws common::IoError.
    void page_out(const RegionKey& key, const ObservationMap& map);
    // The same for a region's section bytes as read from a map file (region_io.hpp, version 2).
    void page_out_section(const RegionKey& key, const std::vector<std::uint8_t>& section,
                          std::size_t voxels);
    // The region back from its file, which is removed. Throws common::IoError / FormatError
    // (a damaged or missing file) and std::out_of_range when the region is not paged out.
    std::unique_ptr<ObservationMap> page_in(const RegionKey& key);

    bool holds(const RegionKey& key) const { return regions_.count(key) != 0; }
    // The region's section bytes (what page_out wrote), to copy into a map file.
    std::vector<std::uint8_t> section(const RegionKey& key) const;

    struct Paged {
        std::size_t voxels = 0, bytes = 0;
    };
    const std::map<RegionKey, Paged>& regions() const { return regions_; }
    std::size_t voxels() const;                           // in the paged-out regions
    std::size_t disk_bytes() const;                       // their files
    std::size_t pages_out() const { return pages_out_; }  // since construction
    std::size_t pages_in() const { return pages_in_; }
    const std::string& dir() const { return dir_; }

  private:
    std::string file_of(const RegionKey& key) const;

    std::string dir_;
    MaintenanceConfig config_;
    std::map<RegionKey, Paged> regions_;
    std::size_t pages_out_ = 0, pages_in_ = 0;
};

}  // namespace ltm::maintenance
