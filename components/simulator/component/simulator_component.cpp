// The simulated test world as a live sensor: publishes `points` (PointCloud2, with per-point time
// `t` when the scenario's sensor has it) and `ground_truth` (PoseStamped) at the sensor's rate,
// or as fast as readers take them; and the robot's motion sensors (simulator/core/proprioception):
// `imu` (sensor_msgs/Imu, frame `imu_frame_id`) at `imu_rate` and `wheel_odometry`
// (nav_msgs/Odometry of `base_frame_id`) at `wheel_rate` (default 0: not published; a launch
// config that sets them gives the odometry its `prior.*` extrinsics too), each scan's sweep
// of samples published just before the scan (a driver hands a scan over after its sweep).
#include <chrono>
#include <deque>
#include <future>
#include <memory>

#include "common/core/progress.hpp"
#include "runtime/component.hpp"
#include "runtime/convert/geometry.hpp"
#include "runtime/convert/imu.hpp"
#include "runtime/convert/odometry.hpp"
#include "runtime/convert/path.hpp"
#include "runtime/convert/pointcloud2.hpp"
#include "runtime/pose_param.hpp"
#include "simulator/core/proprioception.hpp"
#include "simulator/core/random.hpp"
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
        imu_frame_id_ = p.get<std::string>("imu_frame_id", "imu");
        base_frame_id_ = p.get<std::string>("base_frame_id", "base_link");
        wheel_frame_id_ = p.get<std::string>("wheel_frame_id", "wheel_odom");
        imu_config_.rate = p.get<double>("imu_rate", 0.0);
        wheel_config_.rate = p.get<double>("wheel_rate", 0.0);
        if (imu_config_.rate < 0.0) p.fail("imu_rate", "must be >= 0 (0: no IMU)");
        if (wheel_config_.rate < 0.0) p.fail("wheel_rate", "must be >= 0 (0: no wheel odometry)");
        imu_config_.T_lidar_imu = runtime::pose_param(p, "imu_extrinsic", default_imu_mount());
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
        // The base on the ground below the LiDAR unless told otherwise.
        wheel_config_.T_lidar_base.translation() =
            Eigen::Vector3d(0.0, 0.0, -sim_->scenario().sensor.height);
        wheel_config_.T_lidar_base =
            runtime::pose_param(p, "wheel_extrinsic", wheel_config_.T_lidar_base);
        const std::uint64_t motion_seed =
            hash_mix(sim_->scenario().seed, std::uint64_t(session), 0x1A2Bull);  // as ltm_sim
        imu_ = std::make_unique<ImuSimulator>(imu_config_, motion_seed);
        wheel_ = std::make_unique<WheelSimulator>(wheel_config_, motion_seed);
        next_ = next_render_ = first_;
        points_ = ctx.advertise<msg::PointCloud2>("points",
                                                  fast_ ? TopicRole::kStream : TopicRole::kSensor);
        ground_truth_ = ctx.advertise<msg::PoseStamped>("ground_truth", TopicRole::kState);
        // As the scans: lossless when fast, sensor data in real time (a reader of the bursts of
        // a sweep's samples wants a depth of 50 or more: the launch config's topics: entry).
        const TopicRole motion_role = fast_ ? TopicRole::kStream : TopicRole::kSensor;
        if (imu_config_.rate > 0.0) imu_out_ = ctx.advertise<msg::Imu>("imu", motion_role);
        if (wheel_config_.rate > 0.0)
            wheel_out_ = ctx.advertise<msg::Odometry>("wheel_odometry", motion_role);
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
        publish_motion(i);
        scan_ = ahead_.front().get();
        ahead_.pop_front();
        scan_.cloud.frame_id = frame_id_;
        points_.publish(builder_.build(scan_.cloud));
        ground_truth_.publish(*convert::to_msg(
            common::StampedPose{scan_.cloud.stamp, scan_.T_world_lidar}, world_frame_id_));
        progress_->update(i + 1 - first_);
    }

    // The IMU and wheel samples of scan i's sweep (to the next scan, or the sweep's end before a
    // kidnap or at the end), published before the scan.
    void publish_motion(std::size_t i) {
        if (imu_config_.rate <= 0.0 && wheel_config_.rate <= 0.0) return;
        imu_samples_.clear();
        wheel_samples_.clear();
        simulate_proprioception(*sim_, i, i + 1, imu_config_.rate > 0.0 ? imu_.get() : nullptr,
                                wheel_config_.rate > 0.0 ? wheel_.get() : nullptr, &imu_samples_,
                                &wheel_samples_);
        const double gyro_var = imu_config_.gyro_noise * imu_config_.gyro_noise * imu_config_.rate;
        const double accel_var =
            imu_config_.accel_noise * imu_config_.accel_noise * imu_config_.rate;
        for (const ImuSample& s : imu_samples_) {
            imu_out_.publish(*convert::to_msg(
                convert::ImuData{s.stamp, imu_frame_id_, s.gyro, s.accel, gyro_var, accel_var}));
        }
        for (const WheelSample& s : wheel_samples_) {
            convert::OdometryData o;
            o.stamp = convert::to_time(s.stamp);
            o.frame_id = wheel_frame_id_;
            o.child_frame_id = base_frame_id_;
            o.T_parent_child = s.T_odom_base;
            o.linear_velocity = s.linear;
            o.angular_velocity = s.angular;
            wheel_out_.publish(*convert::to_msg(o));
        }
    }

    runtime::ComponentContext& ctx_;
    std::unique_ptr<Simulator> sim_;
    SimScan scan_;
    convert::PointCloud2Builder builder_;
    runtime::Publisher<msg::PointCloud2> points_;
    runtime::Publisher<msg::PoseStamped> ground_truth_;
    runtime::Publisher<msg::Imu> imu_out_;
    runtime::Publisher<msg::Odometry> wheel_out_;
    ImuConfig imu_config_;
    WheelConfig wheel_config_;
    std::unique_ptr<ImuSimulator> imu_;
    std::unique_ptr<WheelSimulator> wheel_;
    std::vector<ImuSample> imu_samples_;
    std::vector<WheelSample> wheel_samples_;
    std::string imu_frame_id_, base_frame_id_, wheel_frame_id_;
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
