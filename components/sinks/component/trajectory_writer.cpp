// Writes the poses it receives as trajectory files: `kitti_file` and/or `tum_file`.
//   input: odometry (nav_msgs/Odometry, default) | pose (geometry_msgs/PoseStamped)
//          | pose_with_covariance (geometry_msgs/PoseWithCovarianceStamped on `pose`: localisation)
//          | path (nav_msgs/Path: the whole file is rewritten with every message)
#include <memory>

#include "common/core/io_error.hpp"
#include "runtime/component.hpp"
#include "runtime/convert/geometry.hpp"
#include "runtime/convert/path.hpp"
#include "sinks/core/trajectory_file.hpp"

namespace ltm::sinks {
namespace {

using runtime::PathCheck;
using runtime::TopicRole;

class TrajectoryWriter : public runtime::Component {
  public:
    explicit TrajectoryWriter(runtime::ComponentContext& ctx) : ctx_(ctx) {
        auto& p = ctx.params();
        const std::string kitti = p.path("kitti_file", "", PathCheck::kParentExists);
        const std::string tum = p.path("tum_file", "", PathCheck::kParentExists);
        if (kitti.empty() && tum.empty()) p.fail("kitti_file", "give kitti_file, tum_file or both");
        const std::string input = p.get<std::string>("input", "odometry");
        try {
            if (!kitti.empty())
                files_.push_back(std::make_unique<TrajectoryFile>(kitti, TrajectoryFormat::kKitti));
            if (!tum.empty())
                files_.push_back(std::make_unique<TrajectoryFile>(tum, TrajectoryFormat::kTum));
        } catch (const common::IoError& e) {
            p.fail(kitti.empty() ? "tum_file" : "kitti_file", e.what());
        }
        if (input == "odometry") {
            ctx.subscribe<msg::Odometry>(
                "odometry", TopicRole::kState, [this](const msg::Odometry& m) {
                    append(convert::to_seconds(m.header.stamp), convert::to_isometry(m.pose.pose));
                });
        } else if (input == "pose") {
            ctx.subscribe<msg::PoseStamped>("pose", TopicRole::kState,
                                            [this](const msg::PoseStamped& m) {
                                                const common::StampedPose p = convert::from_msg(m);
                                                append(p.stamp, p.pose);
                                            });
        } else if (input == "pose_with_covariance") {
            ctx.subscribe<msg::PoseWithCovarianceStamped>(
                "pose", TopicRole::kState, [this](const msg::PoseWithCovarianceStamped& m) {
                    append(convert::to_seconds(m.header.stamp), convert::to_isometry(m.pose.pose));
                });
        } else if (input == "path") {
            ctx.subscribe<msg::Path>("path", TopicRole::kMap, [this](const msg::Path& m) {
                const common::Trajectory t = convert::from_msg(m);
                for (auto& f : files_) f->rewrite(t);
            });
        } else {
            p.fail("input",
                   "expected odometry, pose, pose_with_covariance or path, got '" + input + "'");
        }
    }

    void on_shutdown() override {
        for (auto& f : files_) {
            try {
                f->flush();
                ctx_.log().info("wrote " + std::to_string(f->size()) + " poses to " + f->path());
                ctx_.report_output("trajectory", f->path(), true,
                                   std::to_string(f->size()) + " poses");
            } catch (const std::exception& e) {
                ctx_.report_output("trajectory", f->path(), false, e.what());
            }
        }
    }

  private:
    void append(double stamp, const Eigen::Isometry3d& pose) {
        for (auto& f : files_) f->append(stamp, pose);
    }

    runtime::ComponentContext& ctx_;
    std::vector<std::unique_ptr<TrajectoryFile>> files_;
};

}  // namespace
}  // namespace ltm::sinks

LTM_REGISTER_COMPONENT(ltm::sinks::TrajectoryWriter, "trajectory_writer",
                       "writes received poses (odometry, pose, pose with covariance or path) as "
                       "KITTI and/or TUM files")
