// Components that only the test host links, for the maintenance component's test: a probe that
// writes what it publishes to a text file, and a source of odd scans (empty, with NaN points)
// with their poses.
#include <chrono>
#include <cmath>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "runtime/component.hpp"

namespace ltm::tests {
namespace {

using runtime::TopicRole;

std::string text(const char* s) { return s ? s : ""; }

double seconds(const msg::Time& t) { return t.sec + 1e-9 * t.nanosec; }

// Lines of `file`, one a message:
//   changes STAMP FRAME PASS SESSION VOXEL_SIZE CHANGES VOXELS REMOVED_SEGMENTS ADDED_SEGMENTS
//   event COMPONENT LEVEL CODE MESSAGE
class MapChangesProbe : public runtime::Component {
  public:
    explicit MapChangesProbe(runtime::ComponentContext& ctx) {
        auto& p = ctx.params();
        out_.open(p.path("file", "", runtime::PathCheck::kParentExists));
        if (!out_) p.fail("file", "cannot be written");
        out_.precision(9);
        ctx.subscribe<msg::MapChangeSet>("map_changes", TopicRole::kMap,
                                         [this](const msg::MapChangeSet& m) { on_changes(m); });
        ctx.subscribe<msg::Status>("status", TopicRole::kState, [this](const msg::Status& m) {
            out_ << "event " << text(m.component) << ' ' << int(m.level) << ' ' << text(m.key)
                 << ' ' << text(m.message) << '\n';
        });
    }
    void on_shutdown() override { out_.flush(); }

  private:
    void on_changes(const msg::MapChangeSet& m) {
        std::size_t voxels = 0, removed = 0, added = 0;
        for (std::uint32_t i = 0; i < m.changes._length; ++i) {
            const msg::SegmentChange& c = m.changes._buffer[i];
            voxels += c.voxels._length / 3;
            (c.reason == ltm_msgs_msg_SegmentChange_Constants_NEW ? added : removed) += 1;
        }
        out_ << "changes " << seconds(m.header.stamp) << ' ' << text(m.header.frame_id) << ' '
             << m.pass << ' ' << m.session << ' ' << m.voxel_size << ' ' << m.changes._length << ' '
             << voxels << ' ' << removed << ' ' << added << '\n';
    }

    std::ofstream out_;
};

// Publishes on `points` an empty scan, a scan of NaN points only, and `scans` scans of a wall
// 5 m ahead with a few NaN points among them, each followed by its pose (PoseStamped, frame
// `world`) on `pose` but scan `no_pose` (0-based); then finishes.
class OddScansSource : public runtime::Component {
  public:
    explicit OddScansSource(runtime::ComponentContext& ctx) : ctx_(ctx) {
        scans_ = ctx.params().get<int>("scans", 5);
        no_pose_ = ctx.params().get<int>("no_pose", -1);
        points_ = ctx.advertise<msg::PointCloud2>("points", TopicRole::kStream);
        pose_ = ctx.advertise<msg::PoseStamped>("pose", TopicRole::kState);
        ctx.declare_source();
        ctx.add_timer(0.0, [this] { step(); });
    }

  private:
    void step() {
        if (points_.matched() < 1 || pose_.matched() < 1) {
            ctx_.sleep_until(std::chrono::steady_clock::now() + std::chrono::milliseconds(5));
            return;
        }
        const float nan = std::numeric_limits<float>::quiet_NaN();
        for (int k = 0; k < scans_ + 2; ++k) {
            std::vector<float> xyz;
            if (k == 1) xyz = {nan, nan, nan, nan, 1.0f, 2.0f};
            if (k >= 2) {
                for (int i = 0; i < 40; ++i)
                    for (int j = 0; j < 10; ++j)
                        xyz.insert(xyz.end(), {5.0f, 0.1f * i - 2, 0.1f * j});
                xyz.insert(xyz.end(), {nan, 0.0f, 0.0f});
            }
            publish(100.0 + 0.1 * k, xyz, k != no_pose_);
        }
        ctx_.finished();
    }

    void publish(double stamp, std::vector<float>& xyz, bool with_pose) {
        char x[] = "x", y[] = "y", z[] = "z", lidar[] = "lidar", world[] = "world";
        msg::PointField fields[3] = {{x, 0, 7, 1}, {y, 4, 7, 1}, {z, 8, 7, 1}};
        msg::PointCloud2 m{};
        m.header.stamp.sec = static_cast<std::int32_t>(stamp);
        m.header.stamp.nanosec =
            static_cast<std::uint32_t>(std::lround((stamp - std::floor(stamp)) * 1e9));
        m.header.frame_id = lidar;
        m.height = 1;
        m.width = static_cast<std::uint32_t>(xyz.size() / 3);
        m.fields._buffer = fields;
        m.fields._length = m.fields._maximum = 3;
        m.point_step = 12;
        m.row_step = 12 * m.width;
        m.is_dense = false;
        m.data._buffer = reinterpret_cast<std::uint8_t*>(xyz.data());
        m.data._length = m.data._maximum = static_cast<std::uint32_t>(xyz.size() * 4);
        points_.publish(m);
        if (!with_pose) return;
        msg::PoseStamped p{};
        p.header.stamp = m.header.stamp;
        p.header.frame_id = world;
        p.pose.orientation.w = 1.0;
        pose_.publish(p);
    }

    runtime::ComponentContext& ctx_;
    int scans_ = 5, no_pose_ = -1;
    runtime::Publisher<msg::PointCloud2> points_;
    runtime::Publisher<msg::PoseStamped> pose_;
};

}  // namespace
}  // namespace ltm::tests

LTM_REGISTER_COMPONENT(ltm::tests::MapChangesProbe, "test_map_changes_probe",
                       "test: writes map_changes and status lines to a file")
LTM_REGISTER_COMPONENT(ltm::tests::OddScansSource, "test_odd_scans_source",
                       "test: publishes an empty scan, a NaN scan and a wall, with poses")
