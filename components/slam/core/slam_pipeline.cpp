#include "slam/core/slam_pipeline.hpp"

#include <chrono>

namespace ltm::slam {
namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

}  // namespace

SlamPipeline::SlamPipeline(const SlamPipelineConfig& config)
    : odometry_(config.odometry), mapper_(config.mapping), handover_(config.handover) {}

SlamFrame SlamPipeline::process(const common::PointCloud& cloud) {
    SlamFrame f;
    f.scan_index = scans_++;
    auto t0 = Clock::now();
    f.odometry = odometry_.register_frame(cloud);
    f.odometry_ms = ms_since(t0);
    map_frame(&f);
    return f;
}

SlamFrame SlamPipeline::process(const common::PointCloud& cloud,
                                const Eigen::Isometry3d& T_odom_lidar) {
    SlamFrame f;
    f.scan_index = scans_++;
    auto t0 = Clock::now();
    f.odometry = odometry_.place_frame(cloud, T_odom_lidar);
    f.odometry_ms = ms_since(t0);
    map_frame(&f);
    return f;
}

void SlamPipeline::map_frame(SlamFrame* frame) {
    SlamFrame& f = *frame;
    auto t0 = Clock::now();
    f.handover = handover_.after_frame(odometry_, f.odometry, f.scan_index);
    if (f.handover.keyframe) {
        t0 = Clock::now();
        f.keyframe = mapper_.add_keyframe(*f.handover.keyframe);
        f.keyframe_ms = ms_since(t0);
    }
    // Optimised before the maps are handed over, as the mapping component does on a keyframe: a
    // finished map is folded into an earlier one only on a settled graph.
    if (f.keyframe && f.keyframe->optimisation_due()) {
        t0 = Clock::now();
        f.optimisation = mapper_.optimise();
        f.optimise_ms = ms_since(t0);
    }
    hand_over_maps(f.handover.local_maps, &f.local_maps);
}

mapping::OptimisationSummary SlamPipeline::finish(
    std::vector<mapping::LocalMapResult>* local_maps) {
    std::vector<mapping::LocalMapResult> results;
    hand_over_maps(handover_.finish(odometry_), &results);
    if (local_maps) *local_maps = std::move(results);
    return mapper_.optimise();
}

void SlamPipeline::hand_over_maps(const std::vector<common::LocalMapData>& maps,
                                  std::vector<mapping::LocalMapResult>* results) {
    for (const common::LocalMapData& m : maps) results->push_back(mapper_.add_local_map(m));
}

}  // namespace ltm::slam
