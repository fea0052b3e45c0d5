#pragma once
// The SLAM benchmark's in-process scan source: one session of a simulator scenario rendered scan
// by scan (the next scans ahead on worker threads, as the simulator component does) and handed
// over as its KITTI folder would be: points and intensity in the LiDAR frame, stamps, and the true
// LiDAR poses as the reference. Per-point times are kept only when the scenario's sensor has
// motion distortion: otherwise every point is already where it was at the stamp (like KITTI's
// de-skewed files and `ltm_sim`'s .bin files), and de-skewing it again would distort it.
#include <cstddef>
#include <deque>
#include <future>
#include <memory>
#include <string>

#include "common/core/point_cloud.hpp"
#include "common/core/trajectory_io.hpp"
#include "simulator/core/simulator.hpp"

namespace ltm::mapping::bench {

struct SimSourceOptions {
    std::string scenario;  // YAML file
    int laps = 0;          // > 0: drive the route this many times (route.laps); 0: as the file says
    int session = 0;
    int threads = 1;  // scans rendered ahead
};

class SimSource {
  public:
    // Loads the scenario and builds the world. Throws sim::ScenarioError (one line).
    explicit SimSource(const SimSourceOptions& options);
    ~SimSource();
    SimSource(const SimSource&) = delete;
    SimSource& operator=(const SimSource&) = delete;

    std::size_t size() const { return sim_->num_scans(); }
    // One line: scenario, session, sensor, laps, route length, objects.
    std::string describe() const;
    // True T_world_lidar at every scan's stamp.
    common::PoseList reference() const;
    // Scan i. Fastest when called for 0, 1, 2, ... in order (the next ones are rendering).
    common::PointCloud load(std::size_t i);

  private:
    std::unique_ptr<sim::Simulator> sim_;
    int laps_ = 1;
    int threads_ = 1;
    bool keep_time_ = false;
    std::deque<std::future<sim::SimScan>> ahead_;  // scans next_ .. next_ + size - 1
    std::size_t next_ = 0;
};

}  // namespace ltm::mapping::bench
