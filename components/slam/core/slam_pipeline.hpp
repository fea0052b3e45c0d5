#pragma once
// The SLAM pipeline offline (benchmarks, tests, tools): odometry -> hand-over -> mapper, in one
// thread, one scan at a time, with the hand-over policy the live components use
// (odometry/core/map_handover.hpp): keyframes with their anchors, finished local maps and periodic
// snapshots with their observation times. The graph is optimised when a loop is accepted and at
// finish(). Live, the odometry and mapping components run the same two halves on either side of
// DDS.
#include <cstdint>
#include <optional>
#include <vector>

#include "common/core/point_cloud.hpp"
#include "mapping/core/mapper.hpp"
#include "odometry/core/map_handover.hpp"
#include "odometry/core/odometry.hpp"

namespace ltm::slam {

struct SlamPipelineConfig {
    odometry::OdometryConfig odometry;
    mapping::MapperConfig mapping;
    odometry::HandoverConfig handover;
};

// What one scan did.
struct SlamFrame {
    std::uint64_t scan_index = 0;
    odometry::FrameResult odometry;
    odometry::Handover handover;                      // what went to the mapper
    std::optional<mapping::KeyframeResult> keyframe;  // the mapper's answer to handover.keyframe
    std::vector<mapping::LocalMapResult> local_maps;  // its answers to handover.local_maps
    std::optional<mapping::OptimisationSummary> optimisation;  // when a loop made one due
    double odometry_ms = 0.0, keyframe_ms = 0.0, optimise_ms = 0.0;
};

class SlamPipeline {
  public:
    // Throws the configs' errors (naming the key).
    explicit SlamPipeline(const SlamPipelineConfig& config);

    SlamFrame process(const common::PointCloud& cloud);
    // A scan at a known pose (odometry::Odometry::place_frame: no registration), handed over and
    // mapped the same way. For a map from a given trajectory; do not mix with process(cloud).
    SlamFrame process(const common::PointCloud& cloud, const Eigen::Isometry3d& T_odom_lidar);
    // End of the stream: the active local maps are finished and handed over, the graph optimised.
    mapping::OptimisationSummary finish(std::vector<mapping::LocalMapResult>* local_maps = nullptr);

    const odometry::Odometry& odometry() const { return odometry_; }
    const mapping::Mapper& mapper() const { return mapper_; }
    const odometry::MapHandover& handover() const { return handover_; }
    std::uint64_t scans() const { return scans_; }

  private:
    // The odometry's result of f->odometry handed over to the mapper.
    void map_frame(SlamFrame* f);
    void hand_over_maps(const std::vector<common::LocalMapData>& maps,
                        std::vector<mapping::LocalMapResult>* results);

    odometry::Odometry odometry_;
    mapping::Mapper mapper_;
    odometry::MapHandover handover_;
    std::uint64_t scans_ = 0;
};

}  // namespace ltm::slam
