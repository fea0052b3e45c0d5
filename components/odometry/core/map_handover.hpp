#pragma once
// What the odometry hands to the SLAM back end after each scan, and when (the one policy for the
// odometry component and the offline pipeline):
//   - the keyframe, with its local map's anchor and the scan's index in the stream;
//   - every local map the odometry finished, with the stamps of the scans that updated it
//     (observation times: map maintenance compares them with its voxels' life);
//   - every `snapshot_every_keyframes` keyframes, and after a restart (a new segment), a snapshot
//     of each active local map (finished = false), so that loops can close against the map being
//     built and the back end learns a new segment before its keyframes' loops are judged.
// Revisions count every handed-over map, so a later snapshot or the finished map supersedes an
// earlier one. Call after every Odometry::register_frame(), and finish() at the end of a stream.
#include <cstdint>
#include <map>
#include <optional>
#include <vector>

#include "common/core/local_map_data.hpp"
#include "odometry/core/odometry.hpp"

namespace ltm::odometry {

struct HandoverConfig {
    int snapshot_every_keyframes = 10;  // 0: finished maps only
};

struct Handover {
    std::optional<common::KeyframeData> keyframe;
    std::vector<common::LocalMapData> local_maps;  // finished ones first, then snapshots
};

class MapHandover {
  public:
    explicit MapHandover(const HandoverConfig& config = {});

    // After `odometry` registered scan `scan_index` with result `frame`.
    Handover after_frame(Odometry& odometry, const FrameResult& frame, std::uint64_t scan_index);
    // At the end of the stream: finishes every active local map and hands it over.
    std::vector<common::LocalMapData> finish(Odometry& odometry);

    std::uint64_t keyframes() const { return keyframes_; }
    std::uint64_t local_maps_handed_over() const { return finished_; }

  private:
    void take_finished(Odometry& odometry, std::vector<common::LocalMapData>* out);

    HandoverConfig config_;
    std::map<std::uint32_t, std::vector<double>> seen_;  // local map -> stamps of its scans
    std::uint32_t revision_ = 0;
    std::uint64_t keyframes_ = 0, finished_ = 0;
};

}  // namespace ltm::odometry
