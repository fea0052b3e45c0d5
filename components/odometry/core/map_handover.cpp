#include "odometry/core/map_handover.hpp"

#include "odometry/core/local_map_export.hpp"

namespace ltm::odometry {

MapHandover::MapHandover(const HandoverConfig& config) : config_(config) {}

Handover MapHandover::after_frame(Odometry& odometry, const FrameResult& frame,
                                  std::uint64_t scan_index) {
    Handover h;
    if (frame.pose_valid()) {
        // The scan updated every active map (the odometry integrates into all of them).
        for (const LocalMap& m : odometry.active_local_maps()) seen_[m.id()].push_back(frame.stamp);
    }
    if (frame.keyframe) {
        for (const LocalMap& m : odometry.active_local_maps()) {
            if (m.id() != frame.keyframe->local_map_id) continue;
            h.keyframe = to_keyframe_data(*frame.keyframe, m.T_odom_anchor(), scan_index);
            h.keyframe->segment = m.segment();
            ++keyframes_;
        }
    }
    take_finished(odometry, &h.local_maps);
    const int every = config_.snapshot_every_keyframes;
    // A restart: the new map goes over at once, so that the back end knows its segment (no
    // odometry relation to the maps before) before it judges loops from its keyframes.
    const bool restarted = frame.status == FrameStatus::kRestarted;
    if (restarted || (h.keyframe && every > 0 && keyframes_ % std::uint64_t(every) == 0)) {
        for (const LocalMap& m : odometry.active_local_maps()) {
            h.local_maps.push_back(to_local_map_data(m, ++revision_, false, seen_[m.id()]));
        }
    }
    return h;
}

std::vector<common::LocalMapData> MapHandover::finish(Odometry& odometry) {
    odometry.finish_local_maps();
    std::vector<common::LocalMapData> out;
    take_finished(odometry, &out);
    return out;
}

void MapHandover::take_finished(Odometry& odometry, std::vector<common::LocalMapData>* out) {
    for (const LocalMap& m : odometry.take_finished_local_maps()) {
        out->push_back(to_local_map_data(m, ++revision_, true, seen_[m.id()]));
        seen_.erase(m.id());
        ++finished_;
    }
}

}  // namespace ltm::odometry
