#include "sources/component/scan_player.hpp"

#include <thread>

#include "common/core/io_error.hpp"
#include "runtime/convert/path.hpp"

namespace ltm::sources {

using runtime::PathCheck;
using runtime::TopicRole;

ScanPlayer::ScanPlayer(runtime::ComponentContext& ctx, ScanFormat format) : ctx_(ctx) {
    auto& p = ctx.params();
    ScanFolderConfig cfg;
    cfg.format = format;
    cfg.path = p.path("path", "", PathCheck::kDirExists);
    if (cfg.path.empty()) p.fail("path", "required parameter is missing (the scan folder)");
    cfg.times_file = p.path("times_file", "", PathCheck::kFileExists);
    cfg.poses_file = p.path("poses_file", "", PathCheck::kFileExists);
    cfg.default_period_s = p.get<double>("period_s", 0.1);
    cfg.start = p.get<std::size_t>("start", 0);
    cfg.count = p.get<std::size_t>("count", 0);
    const std::string mode = p.get<std::string>("mode", "realtime");
    if (mode != "realtime" && mode != "fast")
        p.fail("mode", "expected 'realtime' or 'fast', got '" + mode + "'");
    fast_ = mode == "fast";
    rate_ = p.get<double>("rate", 1.0);
    if (rate_ <= 0) p.fail("rate", "must be positive");
    loop_ = p.get<bool>("loop", false);
    wait_for_readers_ = p.get<int>("wait_for_readers", fast_ ? 1 : 0);
    wait_timeout_s_ = p.get<double>("wait_timeout_s", 30.0);
    frame_id_ = p.get<std::string>("frame_id", "lidar");
    world_frame_id_ = p.get<std::string>("world_frame_id", "world");
    if (cfg.default_period_s <= 0) p.fail("period_s", "must be positive");
    try {
        folder_ = std::make_unique<ScanFolder>(cfg);
    } catch (const common::IoError& e) {
        p.fail("path", e.what());
    }
    points_ =
        ctx.advertise<msg::PointCloud2>("points", fast_ ? TopicRole::kStream : TopicRole::kSensor);
    if (folder_->has_poses())
        ground_truth_ = ctx.advertise<msg::PoseStamped>("ground_truth", TopicRole::kState);
    if (fast_ && !ctx.has_role_override("points"))
        ctx.log().warn(
            "mode fast, but the launch config does not give topic 'points' a role (topics: "
            "{points: "
            "stream}): readers may drop scans");
    ctx.declare_source();
    ctx.add_timer(0.0, [this] { step(); });
}

void ScanPlayer::on_activate() {
    ctx_.log().info(
        "playing " + std::to_string(folder_->size()) + " scans from " + folder_->file(0) +
        (fast_ ? " as fast as readers take them" : " in real time x" + std::to_string(rate_)));
    waiting_since_ = std::chrono::steady_clock::now();
}

void ScanPlayer::step() {
    using clock = std::chrono::steady_clock;
    if (waiting_) {
        // Scans published before any reader matched would be lost.
        if (static_cast<int>(points_.matched()) < wait_for_readers_ &&
            clock::now() - waiting_since_ < std::chrono::duration<double>(wait_timeout_s_)) {
            ctx_.sleep_until(clock::now() + std::chrono::milliseconds(5));
            return;
        }
        if (static_cast<int>(points_.matched()) < wait_for_readers_)
            ctx_.log().warn("no reader matched within " + std::to_string(wait_timeout_s_) +
                            " s; playing anyway");
        waiting_ = false;
        start_wall_ = clock::now();
        progress_ =
            std::make_unique<common::Progress>(ctx_.name(), loop_ ? 0 : folder_->size(), "scans");
    }
    if (next_ >= folder_->size()) {
        if (loop_ && folder_->size() > 0) {
            next_ = 0;
            start_wall_ = clock::now();
        } else {
            progress_->finish();
            ctx_.log().info("published " + std::to_string(published_) + " scans (" +
                            std::to_string(skipped_) + " damaged files skipped, " +
                            std::to_string(non_finite_) + " non-finite points dropped)");
            ctx_.finished();
            return;
        }
    }
    const std::size_t i = next_++;
    if (!fast_) {
        const double offset = (folder_->stamp(i) - folder_->stamp(0)) / rate_;
        const auto due = start_wall_ + std::chrono::duration_cast<clock::duration>(
                                           std::chrono::duration<double>(offset));
        if (!ctx_.sleep_until(due)) return;
    }
    common::PointCloud cloud;
    try {
        cloud = folder_->load(i);
    } catch (const common::IoError& e) {
        ++skipped_;
        ctx_.log().warn(std::string("skipping scan: ") + e.what());
        return;
    }
    non_finite_ += common::remove_non_finite(cloud);
    cloud.frame_id = frame_id_;
    if (points_.publish(builder_.build(cloud))) ++published_;
    progress_->update(published_);
    if (ground_truth_.valid()) {
        ground_truth_.publish(
            *convert::to_msg(common::StampedPose{cloud.stamp, folder_->pose(i)}, world_frame_id_));
    }
}

void ScanPlayer::on_shutdown() {
    if (loop_)
        ctx_.log().info("stopped after " + std::to_string(published_) + " scans (looping over " +
                        std::to_string(folder_->size()) + ")");
    else if (next_ < folder_->size())
        ctx_.log().info("stopped after " + std::to_string(published_) + " of " +
                        std::to_string(folder_->size()) + " scans");
}

namespace {
class KittiPlayer : public ScanPlayer {
  public:
    explicit KittiPlayer(runtime::ComponentContext& ctx) : ScanPlayer(ctx, ScanFormat::kKittiBin) {}
};
class CloudFolderPlayer : public ScanPlayer {
  public:
    explicit CloudFolderPlayer(runtime::ComponentContext& ctx)
        : ScanPlayer(ctx, ScanFormat::kCloudFiles) {}
};
}  // namespace

}  // namespace ltm::sources

LTM_REGISTER_COMPONENT(
    ltm::sources::KittiPlayer, "kitti_player",
    "plays a KITTI folder (velodyne/*.bin, times.txt) as PointCloud2 on 'points'")
LTM_REGISTER_COMPONENT(ltm::sources::CloudFolderPlayer, "cloud_folder_player",
                       "plays a folder of .pcd/.ply scans (optional times and poses) on 'points'")
