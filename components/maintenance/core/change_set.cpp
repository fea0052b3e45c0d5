#include "maintenance/core/change_set.hpp"

namespace ltm::maintenance {

const char* reason_name(ChangeReason reason) {
    switch (reason) {
        case ChangeReason::kMoving:
            return "moving";
        case ChangeReason::kVanished:
            return "vanished";
        case ChangeReason::kNew:
            return "new";
    }
    return "unknown";
}

std::size_t ChangeSet::count(ChangeReason reason) const {
    std::size_t n = 0;
    for (const SegmentChange& c : changes) n += c.reason == reason ? 1 : 0;
    return n;
}

std::size_t ChangeSet::removed_voxels_by(ChangeReason reason) const {
    std::size_t n = 0;
    for (const SegmentChange& c : changes)
        if (c.reason == reason && c.removed()) n += c.voxels.size();
    return n;
}

void ChangeSet::append(const ChangeSet& other) {
    changes.insert(changes.end(), other.changes.begin(), other.changes.end());
    voxels_before += other.voxels_before;
    voxels_removed += other.voxels_removed;
    voxels_judged += other.voxels_judged;
    segments += other.segments;
    ground_voxels += other.ground_voxels;
    time_ms += other.time_ms;
}

}  // namespace ltm::maintenance
