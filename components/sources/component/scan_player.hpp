#pragma once
// Plays a folder of scans as sensor_msgs/PointCloud2 on `points` (and, with a poses file, the
// true poses as geometry_msgs/PoseStamped on `ground_truth`).
//   mode: realtime  paced by the scans' times, scaled by `rate`
//   mode: fast      as fast as the readers take them; with the `points` topic set to role
//                   `stream` in the launch config nothing is dropped (back-pressure)
#include <chrono>
#include <memory>

#include "common/core/progress.hpp"
#include "runtime/component.hpp"
#include "runtime/convert/pointcloud2.hpp"
#include "sources/core/scan_folder.hpp"

namespace ltm::sources {

class ScanPlayer : public runtime::Component {
  public:
    ScanPlayer(runtime::ComponentContext& ctx, ScanFormat format);
    void on_activate() override;
    void on_shutdown() override;

  private:
    void step();

    runtime::ComponentContext& ctx_;
    std::unique_ptr<ScanFolder> folder_;
    bool fast_ = false;
    double rate_ = 1.0;
    bool loop_ = false;
    int wait_for_readers_ = 1;
    double wait_timeout_s_ = 30.0;
    std::string frame_id_, world_frame_id_;
    runtime::Publisher<msg::PointCloud2> points_;
    runtime::Publisher<msg::PoseStamped> ground_truth_;
    convert::PointCloud2Builder builder_;
    std::size_t next_ = 0, published_ = 0, skipped_ = 0, non_finite_ = 0;
    std::chrono::steady_clock::time_point start_wall_, waiting_since_;
    bool waiting_ = true;
    std::unique_ptr<common::Progress> progress_;
};

}  // namespace ltm::sources
