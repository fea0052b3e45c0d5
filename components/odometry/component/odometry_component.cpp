// LiDAR odometry as a component: `points` (PointCloud2) in; `odometry` (nav_msgs/Odometry with
// covariance), `keyframe`, `local_map` (finished maps, and snapshots of the active ones, with their
// observation times: the hand-over policy of odometry/core/map_handover.hpp, the same as the
// offline pipeline's) and `status` (skipped, rejected or diverged scans) out. Parameters: the
// odometry's (preset and keys, see odometry/params) plus the frames and the snapshot period.
#include <memory>

#include "odometry/core/map_handover.hpp"
#include "odometry/core/odometry.hpp"
#include "odometry/params/odometry_params.hpp"
#include "runtime/component.hpp"
#include "runtime/convert/geometry.hpp"
#include "runtime/convert/local_map.hpp"
#include "runtime/convert/odometry.hpp"
#include "runtime/convert/pointcloud2.hpp"
#include "runtime/convert/status.hpp"

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
        odometry_ = std::make_unique<Odometry>(load_odometry_config(p));
        ctx.subscribe<msg::PointCloud2>("points", TopicRole::kSensor,
                                        [this](const msg::PointCloud2& m) { on_points(m); });
        odometry_out_ = ctx.advertise<msg::Odometry>("odometry", TopicRole::kState);
        keyframe_out_ = ctx.advertise<msg::Keyframe>("keyframe", TopicRole::kState);
        local_map_out_ = ctx.advertise<msg::LocalMap>("local_map", TopicRole::kMap);
        status_out_ = ctx.advertise<msg::Status>("status", TopicRole::kState);
    }

    void on_shutdown() override {
        // Hand every map on: the active ones are finished here, nothing built is lost.
        for (const common::LocalMapData& m : handover_.finish(*odometry_)) publish_local_map(m);
        ctx_.log().info(std::to_string(frames_) + " scans, " + std::to_string(tracked_) +
                        " tracked, " + std::to_string(degenerate_) +
                        " degenerate (published, along a direction the motion model's), " +
                        std::to_string(frames_ - tracked_ - degenerate_) + " not (see status), " +
                        std::to_string(maps_published_) + " local maps published");
    }

  private:
    void on_points(const msg::PointCloud2& m) {
        const std::uint64_t index = frames_++;
        const std::string err = convert::from_pointcloud2(m, cloud_);
        if (!err.empty()) {
            status(StatusLevel::kError, StatusCode::kBadCloud,
                   "scan " + std::to_string(index) + ": " + err, cloud_.stamp);
            return;
        }
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
    std::unique_ptr<Odometry> odometry_;
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
};

}  // namespace
}  // namespace ltm::odometry

LTM_REGISTER_COMPONENT(
    ltm::odometry::OdometryComponent, "odometry",
    "IMLS LiDAR odometry: PointCloud2 in; odometry, keyframes and local maps out")
