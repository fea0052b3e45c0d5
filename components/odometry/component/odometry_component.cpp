// LiDAR odometry as a component: `points` (PointCloud2) in; `odometry` (nav_msgs/Odometry with
// covariance), `keyframe`, `local_map` (finished maps, and snapshots of the active ones, with their
// observation times: the hand-over policy of odometry/core/map_handover.hpp, the same as the
// offline pipeline's) and `status` (skipped, rejected or diverged scans) out. Parameters: the
// odometry's (preset and keys, see odometry/params) plus the frames and the snapshot period.
// `preset: auto` (the default): the sensor preset is told from the first scans
// (common/core/sensor_detect.hpp) before the first is registered, and said in one line; nothing
// is published before. The keys given apply to whichever preset it is (checked against every
// preset at the start).
// Optional inputs, a motion prior from the robot (odometry/core/motion_prior.hpp): `imu`
// (sensor_msgs/Imu, gyro) and `wheel_odometry` (nav_msgs/Odometry of the base frame), with the
// `prior.*` parameters (the extrinsics `prior.imu_extrinsic`, `prior.wheel_extrinsic` as
// [x, y, z, roll, pitch, yaw] in m and deg: the sensor's frame in the LiDAR frame; noise, gate).
// Without samples on them nothing changes.
#include <memory>
#include <optional>

#include "common/core/sensor_detect.hpp"
#include "odometry/core/map_handover.hpp"
#include "odometry/core/odometry.hpp"
#include "odometry/params/odometry_params.hpp"
#include "runtime/component.hpp"
#include "runtime/convert/geometry.hpp"
#include "runtime/convert/imu.hpp"
#include "runtime/convert/local_map.hpp"
#include "runtime/convert/odometry.hpp"
#include "runtime/convert/pointcloud2.hpp"
#include "runtime/convert/status.hpp"
#include "runtime/pose_param.hpp"

namespace ltm::odometry {
namespace {

using common::StatusCode;
using convert::StatusLevel;
using runtime::TopicRole;

// What the localisation (and whoever listens) reads of a scan's outcome.
StatusCode status_code(FrameStatus status) {
    switch (status) {
        case FrameStatus::kInitialised:
            return StatusCode::kInitialised;
        case FrameStatus::kTracked:
            return StatusCode::kTracked;
        case FrameStatus::kRecovered:
            return StatusCode::kRecovered;
        case FrameStatus::kRestarted:
            return StatusCode::kRestarted;
        case FrameStatus::kDegenerate:
            return StatusCode::kDegenerate;
        case FrameStatus::kLost:
            return StatusCode::kLost;
        case FrameStatus::kSkippedTooFewPoints:
            return StatusCode::kSkipped;
        case FrameStatus::kRejectedStamp:
            return StatusCode::kRejected;
    }
    return StatusCode::kUnknown;
}

// The motion prior's `prior.*` parameters (defaults: MotionPriorConfig's).
MotionPriorConfig load_prior_config(runtime::Parameters& p) {
    MotionPriorConfig c;
    c.T_lidar_imu = runtime::pose_param(p, "prior.imu_extrinsic", c.T_lidar_imu);
    c.T_lidar_base = runtime::pose_param(p, "prior.wheel_extrinsic", c.T_lidar_base);
    c.gyro_noise = p.get<double>("prior.gyro_noise", c.gyro_noise);
    c.gyro_bias = p.get<double>("prior.gyro_bias", c.gyro_bias);
    c.bias_gain = p.get<double>("prior.bias_gain", c.bias_gain);
    c.bias_window = p.get<double>("prior.bias_window", c.bias_window);
    c.wheel_scale = p.get<double>("prior.wheel_scale", c.wheel_scale);
    c.wheel_turn = p.get<double>("prior.wheel_turn", c.wheel_turn);
    c.gate_sigmas = p.get<double>("prior.gate_sigmas", c.gate_sigmas);
    c.gate_rotation = p.get<double>("prior.gate_rotation", c.gate_rotation);
    c.gate_translation = p.get<double>("prior.gate_translation", c.gate_translation);
    c.max_gap = p.get<double>("prior.max_gap", c.max_gap);
    c.keep_seconds = p.get<double>("prior.keep_seconds", c.keep_seconds);
    if (const auto problem = validate(c)) p.fail("prior." + problem->key, problem->problem);
    return c;
}

class OdometryComponent : public runtime::Component {
  public:
    explicit OdometryComponent(runtime::ComponentContext& ctx) : ctx_(ctx) {
        auto& p = ctx.params();
        odom_frame_ = p.get<std::string>("frame_id", "odom");
        child_frame_ = p.get<std::string>("child_frame_id", "lidar");
        HandoverConfig handover;
        handover.snapshot_every_keyframes =
            p.get<int>("snapshot_every_keyframes", handover.snapshot_every_keyframes);
        if (handover.snapshot_every_keyframes < 0)
            p.fail("snapshot_every_keyframes", "must be >= 0 (0: finished maps only)");
        handover_ = MapHandover(handover);
        prior_ = std::make_unique<MotionPrior>(load_prior_config(p));
        named_preset_ = load_odometry_preset(p, "", common::kAutoPreset);
        if (named_preset_) {
            start(load_odometry_config_for(p, "", *named_preset_));
        } else {
            // Every key must suit whichever preset the scans turn out to need: tried on each now.
            for (const common::SensorPreset each : common::kSensorPresets)
                load_odometry_config_for(p, "", each);
        }
        ctx.subscribe<msg::Imu>("imu", TopicRole::kSensor, [this](const msg::Imu& m) {
            convert::ImuData d;
            if (!convert::from_msg(m, &d).empty()) return;
            prior_->add_imu(d.stamp, d.angular_velocity);
            ++imu_samples_;
        });
        ctx.subscribe<msg::Odometry>(
            "wheel_odometry", TopicRole::kSensor, [this](const msg::Odometry& m) {
                const convert::OdometryData d = convert::from_msg(m);
                prior_->add_wheel(convert::to_seconds(d.stamp), d.T_parent_child);
                ++wheel_samples_;
            });
        ctx.subscribe<msg::PointCloud2>("points", TopicRole::kSensor,
                                        [this](const msg::PointCloud2& m) { on_points(m); });
        // The local maps being built, for the host's minute memory line.
        ctx.add_timer(runtime::kMemoryReportPeriod, [this] {
            if (odometry_) ctx_.report_memory("local maps", odometry_->memory_bytes());
        });
        odometry_out_ = ctx.advertise<msg::Odometry>("odometry", TopicRole::kState);
        keyframe_out_ = ctx.advertise<msg::Keyframe>("keyframe", TopicRole::kState);
        local_map_out_ = ctx.advertise<msg::LocalMap>("local_map", TopicRole::kMap);
        status_out_ = ctx.advertise<msg::Status>("status", TopicRole::kState);
    }

    void on_shutdown() override {
        // Hand every map on: the active ones are finished here, nothing built is lost.
        if (!odometry_) {
            ctx_.log().warn(std::to_string(frames_) + " scans, none registered: " +
                            (detector_.scans_seen() ? detector_.line() : "no scan came") +
                            " (preset auto)");
            return;
        }
        for (const common::LocalMapData& m : handover_.finish(*odometry_)) publish_local_map(m);
        ctx_.log().info(std::to_string(frames_) + " scans, " + std::to_string(tracked_) +
                        " tracked, " + std::to_string(degenerate_) +
                        " degenerate (published, along a direction the motion model's), " +
                        std::to_string(frames_ - tracked_ - degenerate_) + " not (see status), " +
                        std::to_string(maps_published_) + " local maps published");
        if (imu_samples_ + wheel_samples_ > 0) {
            const Eigen::Vector3d b = prior_->gyro_bias();
            ctx_.log().info("motion prior: " + std::to_string(imu_samples_) + " IMU and " +
                            std::to_string(wheel_samples_) +
                            " wheel samples; gyro bias learnt (IMU frame) " +
                            std::to_string(b.x()) + " " + std::to_string(b.y()) + " " +
                            std::to_string(b.z()) + " rad/s");
        }
    }

  private:
    void start(const OdometryConfig& config) {
        odometry_ = std::make_unique<Odometry>(config);
        odometry_->set_prior(prior_.get());
    }

    // `preset: auto`: true once the preset is known (the odometry then made with it). A named
    // preset the first scans contradict is said as a warning (it is kept: it was asked for).
    bool sensor_known() {
        if (detector_.decided() || !detector_.add(cloud_)) return odometry_ != nullptr;
        if (named_preset_) {
            if (detector_.detected() && detector_.preset() != *named_preset_)
                ctx_.log().warn("preset " + std::string(common::to_string(*named_preset_)) +
                                " as configured, but the scans look like another sensor's: " +
                                detector_.line());
            return true;
        }
        start(load_odometry_config_for(ctx_.params(), "", detector_.preset()));
        if (detector_.detected()) {
            ctx_.log().info(detector_.line());
        } else {
            ctx_.log().warn(detector_.line());
        }
        return true;
    }

    void on_points(const msg::PointCloud2& m) {
        const std::uint64_t index = frames_++;
        const std::string err = convert::from_pointcloud2(m, cloud_);
        if (!err.empty()) {
            status(StatusLevel::kError, StatusCode::kBadCloud,
                   "scan " + std::to_string(index) + ": " + err, cloud_.stamp);
            return;
        }
        if (!sensor_known()) return;  // an unclassifiable scan: the next one decides
        const FrameResult r = odometry_->register_frame(cloud_);
        if (r.pose_valid()) {
            ++(r.status == FrameStatus::kDegenerate ? degenerate_ : tracked_);
            publish_odometry(r);
        }
        // lost, skipped, rejected: a warning each scan; restarted (a new segment at a guessed
        // pose): a warning; recovered: back on track, said once.
        if (!r.message.empty()) {
            status(r.status == FrameStatus::kRecovered ? StatusLevel::kOk : StatusLevel::kWarn,
                   status_code(r.status), "scan " + std::to_string(index) + ": " + r.message,
                   r.stamp, r.status == FrameStatus::kRestarted ? r.segment : 0);
        }
        if (r.degenerate() && r.status != FrameStatus::kDegenerate)  // else said above
            status(StatusLevel::kWarn, StatusCode::kDegenerate,
                   "scan " + std::to_string(index) + ": " +
                       std::to_string(r.degenerate_directions.size()) + " degenerate direction(s)",
                   r.stamp);
        const Handover h = handover_.after_frame(*odometry_, r, index);
        if (h.keyframe)
            keyframe_out_.publish(keyframes_.build(*h.keyframe, odom_frame_, child_frame_));
        for (const common::LocalMapData& m : h.local_maps) publish_local_map(m);
    }

    void publish_odometry(const FrameResult& r) {
        convert::OdometryData o;
        o.stamp = convert::to_time(r.stamp);
        o.frame_id = odom_frame_;
        o.child_frame_id = child_frame_;
        o.T_parent_child = r.T_odom_lidar;
        o.pose_covariance = r.covariance;
        if (has_last_ && r.stamp > last_stamp_) {
            // Twist in the child frame, from the last two poses.
            const double dt = r.stamp - last_stamp_;
            const Eigen::Isometry3d delta = last_pose_.inverse() * r.T_odom_lidar;
            const Eigen::AngleAxisd aa(delta.rotation());
            o.linear_velocity = delta.translation() / dt;
            o.angular_velocity = aa.axis() * aa.angle() / dt;
        }
        last_pose_ = r.T_odom_lidar;
        last_stamp_ = r.stamp;
        has_last_ = true;
        odometry_out_.publish(*convert::to_msg(o));
    }

    void publish_local_map(const common::LocalMapData& m) {
        const double stamp = m.observation_times.empty() ? 0.0 : m.observation_times.back();
        local_map_out_.publish(maps_.build(m, stamp, odom_frame_));
        maps_published_ += m.finished;
    }

    void status(StatusLevel level, StatusCode code, const std::string& text, double stamp,
                std::uint32_t segment = 0) {
        if (level == StatusLevel::kOk) {
            ctx_.log().info(text);
        } else if (++warnings_ <= 10 || (warnings_ & (warnings_ - 1)) == 0) {
            ctx_.log().warn(text);
        }
        status_out_.publish(*convert::to_msg(convert::StatusData{
            convert::to_time(stamp), odom_frame_, ctx_.name(), level, code, text, segment}));
    }

    runtime::ComponentContext& ctx_;
    std::unique_ptr<MotionPrior> prior_;  // declared first: the odometry points to it
    std::unique_ptr<Odometry> odometry_;  // null until the preset is known (preset: auto)
    std::optional<common::SensorPreset> named_preset_;  // empty: auto
    common::SensorDetector detector_;
    MapHandover handover_;
    std::string odom_frame_, child_frame_;
    common::PointCloud cloud_;
    convert::LocalMapBuilder maps_;
    convert::KeyframeBuilder keyframes_;
    runtime::Publisher<msg::Odometry> odometry_out_;
    runtime::Publisher<msg::Keyframe> keyframe_out_;
    runtime::Publisher<msg::LocalMap> local_map_out_;
    runtime::Publisher<msg::Status> status_out_;
    Eigen::Isometry3d last_pose_ = Eigen::Isometry3d::Identity();
    double last_stamp_ = 0.0;
    bool has_last_ = false;
    std::uint64_t frames_ = 0, tracked_ = 0, degenerate_ = 0, warnings_ = 0, maps_published_ = 0;
    std::uint64_t imu_samples_ = 0, wheel_samples_ = 0;
};

}  // namespace
}  // namespace ltm::odometry

LTM_REGISTER_COMPONENT(
    ltm::odometry::OdometryComponent, "odometry",
    "IMLS LiDAR odometry: PointCloud2 in; odometry, keyframes and local maps out")
