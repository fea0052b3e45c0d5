// A component that only the test host links: it writes what the localisation component says to a
// text file for the test to read, and can play the operator who gives an initial pose.
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "runtime/component.hpp"

namespace ltm::tests {
namespace {

using runtime::TopicRole;

std::string text(const char* s) { return s ? s : ""; }

double seconds(const msg::Time& t) { return t.sec + 1e-9 * t.nanosec; }

// Lines of `file`, one a message:
//   status STAMP STATE POSE_VALID GLOBAL_RAN CONFIDENCE RELOCALISATIONS SKIPPED MESSAGE
//   pose STAMP X Y Z QX QY QZ QW
//   event COMPONENT LEVEL CODE MESSAGE
// With `initial_pose: [x, y, yaw_deg, variance]` it publishes one initial pose (frame
// `initial_pose_frame`) on `initialpose` once the first localisation status came.
class LocalisationProbe : public runtime::Component {
  public:
    explicit LocalisationProbe(runtime::ComponentContext& ctx) {
        auto& p = ctx.params();
        out_.open(p.path("file", "", runtime::PathCheck::kParentExists));
        if (!out_) p.fail("file", "cannot be written");
        out_.precision(9);
        hint_ = p.get<std::vector<double>>("initial_pose", {});
        if (!hint_.empty() && hint_.size() != 4)
            p.fail("initial_pose", "expected [x, y, yaw_deg, variance]");
        hint_frame_ = p.get<std::string>("initial_pose_frame", "map");
        ctx.subscribe<msg::LocalisationStatus>(
            "localisation_status", TopicRole::kState,
            [this](const msg::LocalisationStatus& m) { on_status(m); });
        ctx.subscribe<msg::PoseWithCovarianceStamped>(
            "pose", TopicRole::kState, [this](const msg::PoseWithCovarianceStamped& m) {
                const auto& q = m.pose.pose.orientation;
                const auto& t = m.pose.pose.position;
                out_ << "pose " << seconds(m.header.stamp) << ' ' << t.x << ' ' << t.y << ' ' << t.z
                     << ' ' << q.x << ' ' << q.y << ' ' << q.z << ' ' << q.w << '\n';
            });
        ctx.subscribe<msg::Status>("status", TopicRole::kState, [this](const msg::Status& m) {
            out_ << "event " << text(m.component) << ' ' << int(m.level) << ' ' << text(m.key)
                 << ' ' << text(m.message) << '\n';
        });
        initial_pose_out_ =
            ctx.advertise<msg::PoseWithCovarianceStamped>("initialpose", TopicRole::kState);
    }
    void on_shutdown() override { out_.flush(); }

  private:
    void on_status(const msg::LocalisationStatus& m) {
        out_ << "status " << seconds(m.header.stamp) << ' ' << int(m.state) << ' '
             << int(m.pose_valid) << ' ' << int(m.global_ran) << ' ' << m.confidence << ' '
             << m.relocalisations << ' ' << m.skipped_scans << ' ' << text(m.message) << '\n';
        if (hint_.empty() || sent_) return;
        sent_ = true;
        msg::PoseWithCovarianceStamped h{};
        h.header.stamp = m.header.stamp;
        h.header.frame_id = hint_frame_.data();
        h.pose.pose.position = {hint_[0], hint_[1], 0.0};
        const double half = 0.5 * hint_[2] * M_PI / 180.0;
        h.pose.pose.orientation = {0.0, 0.0, std::sin(half), std::cos(half)};
        h.pose.covariance[0] = h.pose.covariance[7] = hint_[3];
        initial_pose_out_.publish(h);
    }

    std::ofstream out_;
    std::vector<double> hint_;
    std::string hint_frame_;
    bool sent_ = false;
    runtime::Publisher<msg::PoseWithCovarianceStamped> initial_pose_out_;
};

}  // namespace
}  // namespace ltm::tests

LTM_REGISTER_COMPONENT(ltm::tests::LocalisationProbe, "test_localisation_probe",
                       "test: writes localisation status, poses and status lines to a file")
