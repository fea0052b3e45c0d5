#pragma once
// What change records do to a map, applied record by record in the order of the passes: the
// voxels (cells of the maintenance lattice) removed and the voxels added so far. A consumer of
// `map_changes` or of a session's records (a saved map's keeper, a viewer) keeps one to know
// which of its voxels are gone. A record is read and checked whole before anything of it is
// applied: a damaged record, one of another voxel size or one of an earlier session changes
// nothing, and says why in one line.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <set>
#include <string>

#include "maintenance/core/change_set.hpp"

namespace ltm::maintenance {

class ChangeLedger {
  public:
    explicit ChangeLedger(float voxel_size);

    // The one-line reason why `changes` cannot be applied, or "" when it can.
    std::string refusal(const ChangeSet& changes) const;
    // Applies `changes` (removed voxels leave the added ones, added voxels leave the removed
    // ones). Throws std::invalid_argument with refusal() when it cannot, before changing anything.
    void apply(const ChangeSet& changes);
    // Reads the record at `path` (change_record.hpp) and applies it. Throws common::IoError
    // (unreadable) or common::FormatError (damaged, or refused) and then changes nothing.
    void apply_record(const std::string& path);

    bool removed(const Eigen::Vector3f& p) const;  // world frame
    bool added(const Eigen::Vector3f& p) const;
    std::size_t removed_voxels() const { return removed_.size(); }
    std::size_t added_voxels() const { return added_.size(); }
    std::size_t records() const { return records_; }
    std::uint32_t session() const { return session_; }
    float voxel_size() const { return voxel_size_; }

    bool operator==(const ChangeLedger& o) const;
    bool operator!=(const ChangeLedger& o) const { return !(*this == o); }

  private:
    using Key = std::array<std::int32_t, 3>;
    Key key(const Eigen::Vector3f& p) const;

    float voxel_size_;
    std::set<Key> removed_, added_;
    std::size_t records_ = 0;
    std::uint32_t session_ = 0;
};

}  // namespace ltm::maintenance
