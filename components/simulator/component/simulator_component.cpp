// The simulated test world as a live sensor: publishes `points` (PointCloud2, with per-point time
// `t` when the scenario's sensor has it) and `ground_truth` (PoseStamped) at the sensor's rate,
// or as fast as readers take them.
#include <chrono>
#include <deque>
#include <future>
#include <memory>

#include "common/core/progress.hpp"
#include "runtime/component.hpp"
#include "runtime/convert/path.hpp"
#include "runtime/convert/pointcloud2.hpp"
#include "simulator/core/scenario_yaml.hpp"
#include "simulator/core/simulator.hpp"

namespace ltm::sim {
namespace {

using runtime::PathCheck;
using runtime::TopicRole;

class SimulatorComponent : public runtime::Component {
  public:
    explicit SimulatorComponent(runtime::ComponentContext& ctx) : ctx_(ctx) {
        auto& p = ctx.params();
        const std::string path = p.path("scenario", "", PathCheck::kFileExists);
        if (path.empty()) p.fail("scenario", "required parameter is missing (a scenario .yaml)");
        const int session = p.get<int>("session", 0);
        const long seed = p.get<long>("seed", -1);
        const std::string sensor = p.get<std::string>("sensor", "");
        const std::string mode = p.get<std::string>("mode", "realtime");
        if (mode != "realtime" && mode != "fast")
            p.fail("mode", "expected 'realtime' or 'fast', got '" + mode + "'");
        fast_ = mode == "fast";
        rate_ = p.get<double>("rate", 1.0);
        if (rate_ <= 0) p.fail("rate", "must be positive");
        first_ = p.get<std::size_t>("start", 0);
        const std::size_t count = p.get<std::size_t>("count", 0);
        wait_for_readers_ = p.get<int>("wait_for_readers", fast_ ? 1 : 0);
        threads_ = p.get<int>("threads", 2);
        if (threads_ < 1) p.fail("threads", "must be at least 1");
        frame_id_ = p.get<std::string>("frame_id", "lidar");
        world_frame_id_ = p.get<std::string>("world_frame_id", "world");
        try {
            ScenarioConfig sc = load_scenario(path);
            if (seed >= 0) sc.seed = static_cast<std::uint64_t>(seed);
            if (!sensor.empty() && !replace_sensor(sensor, sc.sensor))
                p.fail("sensor",
                       "unknown sensor '" + sensor + "' (known: " + sensor_preset_names() + ")");
            sim_ = std::make_unique<Simulator>(sc, session);
        } catch (const ScenarioError& e) {
            p.fail("scenario", e.what());
        }
        for (const auto& w : sim_->warnings()) ctx.log().warn(w);
        if (first_ >= sim_->num_scans())
            p.fail("start", "past the last scan (" + std::to_string(sim_->num_scans()) + " scans)");
        last_ = count ? std::min(sim_->num_scans(), first_ + count) : sim_->num_scans();
        next_ = next_render_ = first_;
        points_ = ctx.advertise<msg::PointCloud2>("points",
                                                  fast_ ? TopicRole::kStream : TopicRole::kSensor);
        ground_truth_ = ctx.advertise<msg::PoseStamped>("ground_truth", TopicRole::kState);
        ctx.declare_source();
        ctx.add_timer(0.0, [this] { step(); });
    }

  private:
    void step() {
        using clock = std::chrono::steady_clock;
        if (!progress_) {
            if (static_cast<int>(points_.matched()) < wait_for_readers_ &&
                clock::now() - created_ < std::chrono::seconds(30)) {
                ctx_.sleep_until(clock::now() + std::chrono::milliseconds(5));
                return;
            }
            progress_ = std::make_unique<common::Progress>(ctx_.name(), last_ - first_, "scans");
            start_wall_ = clock::now();
        }
        if (next_ >= last_) {
            progress_->finish();
            ctx_.finished();
            return;
        }
        const std::size_t i = next_++;
        if (!fast_) {
            const double offset = (sim_->stamp(i) - sim_->stamp(first_)) / rate_;
            if (!ctx_.sleep_until(start_wall_ + std::chrono::duration_cast<clock::duration>(
                                                    std::chrono::duration<double>(offset))))
                return;
        }
        // Scans are rendered ahead on `threads_` workers (Simulator::scan is a pure function).
        while (ahead_.size() < static_cast<std::size_t>(threads_) && next_render_ < last_) {
            const std::size_t k = next_render_++;
            ahead_.push_back(std::async(std::launch::async, [this, k] {
                SimScan s;
                sim_->scan(k, s);
                return s;
            }));
        }
        scan_ = ahead_.front().get();
        ahead_.pop_front();
        scan_.cloud.frame_id = frame_id_;
        points_.publish(builder_.build(scan_.cloud));
        ground_truth_.publish(*convert::to_msg(
            common::StampedPose{scan_.cloud.stamp, scan_.T_world_lidar}, world_frame_id_));
        progress_->update(i + 1 - first_);
    }

    runtime::ComponentContext& ctx_;
    std::unique_ptr<Simulator> sim_;
    SimScan scan_;
    convert::PointCloud2Builder builder_;
    runtime::Publisher<msg::PointCloud2> points_;
    runtime::Publisher<msg::PoseStamped> ground_truth_;
    std::unique_ptr<common::Progress> progress_;
    bool fast_ = false;
    double rate_ = 1.0;
    int wait_for_readers_ = 0, threads_ = 2;
    std::size_t first_ = 0, last_ = 0, next_ = 0, next_render_ = 0;
    std::deque<std::future<SimScan>> ahead_;
    std::string frame_id_, world_frame_id_;
    std::chrono::steady_clock::time_point start_wall_, created_ = std::chrono::steady_clock::now();
};

}  // namespace
}  // namespace ltm::sim

LTM_REGISTER_COMPONENT(ltm::sim::SimulatorComponent, "simulator",
                       "the simulated test world as a live LiDAR: PointCloud2 on 'points', true "
                       "poses on 'ground_truth'")
