// Publishes the robot's transform tree for ROS tools and Foxglove: `tf` (tf2_msgs/TFMessage:
// map -> odom from the localisation or the SLAM, odom -> base_link from the odometry, at every
// odometry pose) and `tf_static` (base_link -> lidar, the extrinsic of the launch config,
// transient-local). ROS 2 tools read /tf and /tf_static: remap tf: /tf, tf_static: /tf_static.
#include <memory>

#include "runtime/component.hpp"
#include "runtime/convert/dds_string.hpp"
#include "runtime/convert/geometry.hpp"
#include "runtime/convert/odometry.hpp"
#include "runtime/convert/transform.hpp"
#include "runtime/pose_param.hpp"
#include "transforms/core/transform_tree.hpp"

namespace ltm::transforms {
namespace {

using runtime::TopicRole;

void fill(const Transform& t, msg::TransformStamped& out) {
    out.header.stamp = convert::to_time(t.stamp);
    convert::set_string(out.header.frame_id, t.parent);
    convert::set_string(out.child_frame_id, t.child);
    out.transform = convert::to_transform(t.T_parent_child);
}

convert::Owned<msg::TFMessage> to_msg(const std::vector<Transform>& transforms) {
    convert::Owned<msg::TFMessage> m;
    msg::TransformStamped* out = convert::alloc_sequence(m->transforms, transforms.size());
    for (std::size_t i = 0; i < transforms.size(); ++i) {
        out[i] = msg::TransformStamped{};  // zeroed: its strings are set below
        fill(transforms[i], out[i]);
    }
    return m;
}

FrameNames frame_names(runtime::Parameters& p) {
    FrameNames n;
    n.map = p.get<std::string>("map_frame", n.map);
    n.odom = p.get<std::string>("odom_frame", n.odom);
    n.base = p.get<std::string>("base_frame", n.base);
    n.lidar = p.get<std::string>("lidar_frame", n.lidar);
    for (const std::string* f : {&n.map, &n.odom, &n.base, &n.lidar}) {
        if (f->empty()) p.fail("base_frame", "frame names must not be empty");
    }
    return n;
}

class TfPublisher : public runtime::Component {
  public:
    explicit TfPublisher(runtime::ComponentContext& ctx)
        : ctx_(ctx),
          tree_(frame_names(ctx.params()),
                runtime::pose_param(ctx.params(), "base_to_lidar", Eigen::Isometry3d::Identity())) {
        tf_out_ = ctx.advertise<msg::TFMessage>("tf", TopicRole::kState);
        static_out_ = ctx.advertise<msg::TFMessage>("tf_static", TopicRole::kMap);
        ctx.subscribe<msg::Odometry>("odometry", TopicRole::kState, [this](const msg::Odometry& m) {
            const convert::OdometryData o = convert::from_msg(m);
            std::string problem;
            const auto transforms = tree_.on_odometry(convert::to_seconds(o.stamp), o.frame_id,
                                                      o.child_frame_id, o.T_parent_child, &problem);
            if (transforms.empty()) return refuse(problem);
            tf_out_.publish(*to_msg(transforms));
        });
        ctx.subscribe<msg::TransformStamped>(
            "map_to_odom", TopicRole::kState, [this](const msg::TransformStamped& m) {
                const convert::TransformData t = convert::from_msg(m);
                std::string problem;
                const auto transform =
                    tree_.on_map_to_odom(convert::to_seconds(t.stamp), t.parent_frame_id,
                                         t.child_frame_id, t.T_parent_child, &problem);
                if (!transform) return refuse(problem);
                tf_out_.publish(*to_msg({*transform}));
            });
    }

    void on_activate() override {
        static_out_.publish(*to_msg({tree_.static_transform()}));
        const FrameNames& n = tree_.names();
        ctx_.log().info("transform tree " + n.map + " -> " + n.odom + " -> " + n.base + " -> " +
                        n.lidar + " on tf and tf_static");
    }

    void on_shutdown() override {
        if (refused_ > 0) {
            ctx_.log().warn(std::to_string(refused_) +
                            " poses not in the tree (first: " + first_problem_ + ")");
        }
    }

  private:
    void refuse(const std::string& problem) {
        if (refused_++ == 0) {
            first_problem_ = problem;
            ctx_.log().warn("not in the transform tree: " + problem);
        }
    }

    runtime::ComponentContext& ctx_;
    TransformTree tree_;
    runtime::Publisher<msg::TFMessage> tf_out_, static_out_;
    std::size_t refused_ = 0;
    std::string first_problem_;
};

}  // namespace
}  // namespace ltm::transforms

LTM_REGISTER_COMPONENT(ltm::transforms::TfPublisher, "tf_publisher",
                       "the transform tree map -> odom -> base_link -> lidar on tf and tf_static "
                       "(from odometry, map_to_odom and the base's extrinsic)")
