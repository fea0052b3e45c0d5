// The robot's side of the mapping's keyframe input over a narrow link: each `keyframe` (the
// odometry's, with its whole down-sampled scan) goes out on `digest/keyframe` with the mapping's
// two descriptors made from that scan and only the points a loop verification registers
// (mapping/core/keyframe_digest.hpp): the base station's mapping decides as it would on the
// whole scan, for a fraction of the bytes. Its parameters are the base station mapping's (`preset`
// and any `scan_context.*`, `localisation_descriptor.*`, `verification.*` it sets; the others are
// accepted and not used): a mapping whose descriptors are made otherwise says so and makes them
// again from the points it gets. robot.yaml puts it between the odometry and the uplink.
#include "common/core/sensor_detect.hpp"
#include "mapping/component/place_descriptor_msg.hpp"
#include "mapping/core/keyframe_digest.hpp"
#include "mapping/params/mapper_params.hpp"
#include "runtime/component.hpp"
#include "runtime/convert/dds_string.hpp"
#include "runtime/convert/local_map.hpp"

namespace ltm::mapping {
namespace {

using runtime::TopicRole;

class KeyframeDigestComponent : public runtime::Component {
  public:
    explicit KeyframeDigestComponent(runtime::ComponentContext& ctx)
        : ctx_(ctx), digester_(load_mapper_config(ctx.params(), "", common::kAutoPreset)) {
        out_ = ctx.advertise<msg::Keyframe>("digest/keyframe", TopicRole::kState);
        ctx.subscribe<msg::Keyframe>("keyframe", TopicRole::kState,
                                     [this](const msg::Keyframe& m) { on_keyframe(m); });
    }

    void on_shutdown() override {
        if (keyframes_ == 0) return;
        ctx_.log().info(std::to_string(keyframes_) + " keyframes digested: " +
                        std::to_string(points_in_ / keyframes_) + " points each on average, " +
                        std::to_string(points_out_ / keyframes_) + " sent");
    }

  private:
    void on_keyframe(const msg::Keyframe& m) {
        common::KeyframeData k = convert::from_msg(m);
        digester_.digest(k.points, &descriptors_, &sampled_);
        points_in_ += k.points.size();
        points_out_ += sampled_.size();
        ++keyframes_;
        k.points.swap(sampled_);
        msg::Keyframe out = builder_.build(k, convert::to_string(m.header.frame_id),
                                           convert::to_string(m.points.header.frame_id));
        borrow_into(descriptors_.loop, &out.descriptor);
        borrow_into(descriptors_.localisation, &out.localisation_descriptor);
        out_.publish(out);
    }

    runtime::ComponentContext& ctx_;
    KeyframeDigester digester_;
    KeyframeDescriptors descriptors_;
    std::vector<Eigen::Vector3f> sampled_;
    convert::KeyframeBuilder builder_;
    runtime::Publisher<msg::Keyframe> out_;
    std::uint64_t keyframes_ = 0, points_in_ = 0, points_out_ = 0;
};

}  // namespace
}  // namespace ltm::mapping

LTM_REGISTER_COMPONENT(ltm::mapping::KeyframeDigestComponent, "keyframe_digest",
                       "robot side: keyframes with the mapping's descriptors and only the points "
                       "its loop verification uses (for a narrow link)")
