// Localisation on a saved map as a component: `points` (PointCloud2) and `odometry` (the odometry
// component's nav_msgs/Odometry) in, the map directory a parameter; out `localisation_status`
// (ltm_msgs/LocalisationStatus, every processed scan), `pose` (PoseWithCovarianceStamped in frame
// `map`, while the pose is valid), `map_to_odom` (TransformStamped map -> the odometry's frame) and
// the state changes (lost, relocalised, off the map) on the shared `status`. An initial pose on
// `initialpose` (RViz's "2D Pose Estimate") narrows the next global localisation. With `site_dir`
// instead of `map`, the site's start version's map; when the site is anchored, every valid pose
// also goes out in the site's frame on `site_pose`.
//
// Threads: the component's thread takes every input as it comes and pairs each scan with the
// odometry pose of the same stamp: a scan waits until that pose comes, or the odometry says it has
// none for it (a newer pose, or a status line of that scan saying lost or skipped); while no
// odometry runs (none matched), at most odometry_wait_s of wall time. The localiser runs on a
// worker thread of its own, one scan at a time, because a global localisation takes a while (~0.5
// s) and the inputs must not pile up behind it meanwhile. With skip_while_busy (default: a live
// sensor) a scan that arrives while the worker is busy replaces the one waiting for it (the newest
// scan is processed next, the skipped ones are counted); without it (offline runs) the component's
// thread waits until each scan is done: back-pressure on the sensor, nothing skipped, and the host
// sees the component busy until its last scan is localised.
//
// A large map takes seconds to load. Offline (skip_while_busy false) it is loaded when the
// component is configured: the host starts nothing before it is ready. Live, the worker loads it
// when the component starts: the other components do not wait for it, and the newest scan waits
// for it. A missing or damaged map does not stop the host: the component stays up, says why in one
// line (log, `status`, and every scan's `localisation_status`) and localises nothing.
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <mutex>
#include <optional>

#include "common/core/one_line.hpp"
#include "localisation/component/localisation_messages.hpp"
#include "localisation/component/localiser_params.hpp"
#include "map/core/site_anchor.hpp"
#include "map/core/site_store.hpp"
#include "odometry/core/odometry_config.hpp"
#include "odometry/params/odometry_params.hpp"
#include "registration/core/preprocess.hpp"
#include "runtime/component.hpp"
#include "runtime/convert/dds_string.hpp"
#include "runtime/convert/geometry.hpp"
#include "runtime/convert/odometry.hpp"
#include "runtime/convert/pointcloud2.hpp"
#include "runtime/convert/status.hpp"
#include "runtime/convert/transform.hpp"
#include "runtime/stamp_pairer.hpp"
#include "runtime/worker.hpp"

namespace ltm::localisation {
namespace {

using common::StatusCode;
using convert::StatusLevel;
using runtime::PathCheck;
using runtime::StopToken;
using runtime::TopicRole;

constexpr double kSameStamp = 1e-4;          // a scan and its odometry pose [s]
constexpr std::size_t kMaxOdometry = 200;    // odometry poses kept for pairing
constexpr std::uint64_t kNoMapRepeat = 100;  // the no-map line again on `status` every N scans

// The odometry's settings as this host's odometry component runs them (its preset and every key it
// is given: an `odometry.voxel_size` override reaches the localisation's preprocessing too), else
// the localisation preset's (no odometry component here, or more than one). Says which in the log.
odometry::OdometryConfig odometry_in_use(runtime::ComponentContext& ctx,
                                         common::SensorPreset preset) {
    const runtime::LaunchConfig& launch = ctx.launch_config();
    std::vector<const runtime::ComponentSpec*> found;
    for (const runtime::ComponentSpec& c : launch.components)
        if (c.type == "odometry") found.push_back(&c);
    odometry::OdometryConfig oc = odometry::preset_config(preset);
    std::string from = std::string("preset ") + common::to_string(preset) + " (" +
                       (found.empty() ? "no" : std::to_string(found.size())) +
                       " odometry components in this host)";
    if (found.size() == 1) {
        runtime::Parameters params(found[0]->params, launch.file, found[0]->name);
        oc = odometry::load_odometry_config(params);  // as the odometry component reads them
        from = "odometry component '" + found[0]->name + "'";
    }
    char text[200];
    std::snprintf(text, sizeof text, "scans preprocessed as by the %s: voxel_size %.3g m",
                  from.c_str(), oc.voxel_size);
    ctx.log().info(text);
    return oc;
}

// A scan on its way to the worker, with the odometry's pose and twist when they came in time.
struct Scan {
    std::uint64_t index = 0;
    common::PointCloud cloud;
    std::optional<OdometryInput> odometry;
    registration::Vector6d velocity = registration::Vector6d::Zero();  // [v; w], LiDAR frame
};

using Worker = runtime::Worker<Scan, PoseHint>;

class LocalisationComponent : public runtime::Component {
  public:
    explicit LocalisationComponent(runtime::ComponentContext& ctx) : ctx_(ctx) {
        auto& p = ctx.params();
        frame_id_ = p.get<std::string>("frame_id", "map");
        skip_while_busy_ = p.get<bool>("skip_while_busy", true);
        odometry_wait_s_ = p.get<double>("odometry_wait_s", 1.0);
        if (!(odometry_wait_s_ >= 0)) p.fail("odometry_wait_s", "must be >= 0 (0: do not wait)");
        hint_radius_.sigmas = p.get<double>("initial_pose.sigmas", hint_radius_.sigmas);
        hint_radius_.min_radius = p.get<double>("initial_pose.min_radius", hint_radius_.min_radius);
        if (!(hint_radius_.sigmas > 0)) p.fail("initial_pose.sigmas", "must be > 0");
        if (!(hint_radius_.min_radius > 0)) p.fail("initial_pose.min_radius", "must be > 0");
        preset_ = load_sensor_preset(p);
        config_ = load_localiser_config(p, preset_);
        const odometry::OdometryConfig oc = odometry_in_use(ctx, preset_);
        preprocessor_.emplace(oc.preprocess, oc.voxel_size);
        map_dir_ = p.path("map", "", PathCheck::kNone);
        resolve_site_map(p);
        if (map_dir_.empty() && map_state_ != kFailed)
            p.fail("map", "required: the saved map directory to localise on (map_dir of mapping)");
        if (!skip_while_busy_ && map_state_ == kLoading) load_map();
        pairer_.emplace(runtime::StampPairerOptions{kSameStamp, kMaxOdometry, 0, kMaxOdometry,
                                                    odometry_wait_s_});
        // Live: a scan that comes while the worker is busy replaces the one waiting for it.
        worker_.emplace(
            runtime::WorkerOptions{
                ctx.name(), "work", 1,
                skip_while_busy_ ? runtime::BusyPolicy::kDropOldest : runtime::BusyPolicy::kBlock},
            [this](Worker::Step& step, const StopToken&) { work(step); },
            [this](const std::string& what) {
                event(StatusLevel::kError, StatusCode::kLocalisationFailed, common::one_line(what),
                      0.0);
            });

        ctx.subscribe<msg::PointCloud2>("points", TopicRole::kSensor,
                                        [this](const msg::PointCloud2& m) { on_points(m); });
        ctx.subscribe<msg::Odometry>("odometry", TopicRole::kState,
                                     [this](const msg::Odometry& m) { on_odometry(m); });
        ctx.subscribe<msg::PoseWithCovarianceStamped>(
            "initialpose", TopicRole::kState,
            [this](const msg::PoseWithCovarianceStamped& m) { on_initial_pose(m); });
        // The odometry's restarts (a new segment: its frame is no longer the same).
        ctx.subscribe<msg::Status>("status", TopicRole::kState,
                                   [this](const msg::Status& m) { on_status(m); });
        status_out_ =
            ctx.advertise<msg::LocalisationStatus>("localisation_status", TopicRole::kState);
        pose_out_ = ctx.advertise<msg::PoseWithCovarianceStamped>("pose", TopicRole::kState);
        correction_out_ = ctx.advertise<msg::TransformStamped>("map_to_odom", TopicRole::kState);
        events_out_ = ctx.advertise<msg::Status>("status", TopicRole::kState);
        // A lifelong session on a new site: the map is being made today, and the SLAM's pose
        // (`slam_odometry`: the mapping's corrected_odometry, frame map) is the map pose.
        // Its map -> odom (`slam_map_to_odom`: the mapping's map_to_odom) is then the map's too.
        if (on_site_) {
            ctx.subscribe<msg::Odometry>("slam_odometry", TopicRole::kState,
                                         [this](const msg::Odometry& m) { on_slam_pose(m); });
            ctx.subscribe<msg::TransformStamped>("slam_map_to_odom", TopicRole::kState,
                                                 [this](const msg::TransformStamped& m) {
                                                     if (new_site_) correction_out_.publish(m);
                                                 });
        }
        // Scans whose odometry is late: looked at a few times within odometry_wait_s.
        if (odometry_wait_s_ > 0)
            ctx.add_timer(std::max(0.02, odometry_wait_s_ / 4), [this] { pair(); });
    }

    ~LocalisationComponent() override {
        if (worker_) worker_->stop();
    }

    void on_activate() override {
        // Live, the map is the worker's first job.
        worker_->start([this](const StopToken&) {
            if (map_state_ == kLoading) load_map();
        });
    }

    void on_shutdown() override {
        // Scans still waiting for their odometry go without it.
        if (worker_->started())
            pairer_->release_all([this](double, Scan&& s, std::optional<convert::OdometryData>&&) {
                submit(std::move(s));
            });
        worker_->stop(ctx_.work_deadline());
        const StatusCounters c = counters();
        ctx_.log().info(std::to_string(scans_) + " scans: " + std::to_string(processed_) +
                        " localised (" + std::to_string(valid_) + " with a valid pose), " +
                        std::to_string(c.relocalisations) + " relocalisations, " +
                        std::to_string(c.skipped_scans) + " skipped while busy");
    }

  private:
    // With `site_dir` (map/core/site_store.hpp), the map is the start version's of the site
    // (`site_version`, or the newest intact one); a site without a version yet (a new site):
    // nothing to localise on in this session, said once. A site with an anchor
    // (map/core/site_anchor.hpp) also gets every valid pose in its frame `site` on `site_pose`. A
    // named version that is unknown or damaged refuses the component in one line.
    void resolve_site_map(runtime::Parameters& p) {
        const std::string site = p.path("site_dir", "", PathCheck::kNone);
        const std::string version = p.get<std::string>("site_version", "");
        if (site.empty()) {
            if (!version.empty()) p.fail("site_version", "needs site_dir");
            return;
        }
        on_site_ = true;
        if (!map_dir_.empty()) p.fail("map", "give either map or site_dir, not both");
        map::SiteSession session;
        try {
            session = map::resolve_site(site, version);
        } catch (const common::IoError& e) {
            p.fail(version.empty() ? "site_dir" : "site_version", e.what());
        }
        for (const std::string& note : session.notes) ctx_.log().warn(note);
        try {
            if (const auto anchor = map::read_anchor(site)) {
                T_site_map_ = anchor->T_site_map;
                site_pose_out_ =
                    ctx_.advertise<msg::PoseWithCovarianceStamped>("site_pose", TopicRole::kState);
                ctx_.log().info("site " + site + ": anchored (" + map::anchor_file(site) +
                                "): the pose in frame `site` on site_pose too");
            }
        } catch (const common::IoError& e) {
            p.fail("site_dir", e.what());
        }
        if (session.start) {
            map_dir_ = session.start->map_dir();
            ctx_.log().info("site " + site + ": localising on " + session.describe());
            return;
        }
        new_site_ = true;
        no_map_ =
            "new site: no map yet, nothing to localise on until the next session (the "
            "SLAM's pose, slam_odometry, is the map pose meanwhile)";
        ctx_.log().info("site " + site + ": " + no_map_);
        map_state_ = kFailed;
    }

    // The worker's first job: the map, or why there is none (no_map_): the component then runs
    // and localises nothing.
    void load_map() {
        const auto t0 = std::chrono::steady_clock::now();
        const std::string& dir = map_dir_;
        ctx_.log().info("loading the map " + dir);
        std::shared_ptr<const LocalisationMap> map;
        try {
            std::vector<std::string> refused;
            map = load_localisation_map(dir, localisation_map_preset(preset_), &refused);
            for (const std::string& r : refused) ctx_.log().warn("map: " + r + " (left out)");
            localiser_ = std::make_unique<Localiser>(map, config_);
        } catch (const std::exception& e) {
            no_map_ = "no map to localise on: " + common::one_line(e.what());
            ctx_.log().error(no_map_ + " (the component runs and localises nothing)");
            map_state_ = kFailed;
            return;
        }
        map_state_ = kReady;
        const double s =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        char text[300];
        std::snprintf(text, sizeof text,
                      "map %s: %zu keyframes, %zu local maps, %zu voxels, loaded in %.2f s",
                      dir.c_str(), map->keyframes().size(), map->local_maps(),
                      map->voxels().voxels.size(), s);
        ctx_.log().info(text);
    }

    // --- the component's thread: inputs, pairing ---

    void on_points(const msg::PointCloud2& m) {
        const std::uint64_t index = scans_++;
        if (new_site_) return;  // the SLAM's poses are published as they come (on_slam_pose)
        if (map_state_ == kFailed) {
            publish_no_map(convert::to_seconds(m.header.stamp));
            return;
        }
        Scan scan;
        scan.index = index;
        const std::string err = convert::from_pointcloud2(m, scan.cloud);
        if (!err.empty()) {
            event(StatusLevel::kError, StatusCode::kBadCloud,
                  "scan " + std::to_string(index) + ": " + err, scan.cloud.stamp);
            return;
        }
        if (!(scan.cloud.stamp > newest_scan_)) {  // a repeated or reordered scan
            event(StatusLevel::kWarn, StatusCode::kRejected,
                  "scan " + std::to_string(index) + ": its stamp is not after the previous scan's",
                  scan.cloud.stamp);
            return;
        }
        newest_scan_ = scan.cloud.stamp;
        const double stamp = scan.cloud.stamp;
        pairer_->add_scan(stamp, std::move(scan));
        pair();
    }

    void on_odometry(const msg::Odometry& m) {
        convert::OdometryData o = convert::from_msg(m);
        if (!o.frame_id.empty() && o.frame_id != odom_frame_seen_) {
            odom_frame_seen_ = o.frame_id;
            std::lock_guard<std::mutex> lock(mutex_);
            odom_frame_ = o.frame_id;
        }
        const double stamp = convert::to_seconds(o.stamp);
        pairer_->add_pose(stamp, std::move(o));
        pair();
    }

    // Hands on every waiting scan whose odometry came (with its pose and twist), or will not come
    // (see the file comment).
    void pair() {
        // While an odometry runs (its writer matched), its pose of each scan, a newer one or its
        // "no pose" status will come: wait for it, however late (a loaded machine's odometry was
        // more than odometry_wait_s behind and scans went on without their poses: tracking from
        // a guess, wrong fixes). Without one, odometry_wait_s of wall time.
        pairer_->set_wait_s(ctx_.matched_publishers("odometry") > 0
                                ? std::numeric_limits<double>::infinity()
                                : odometry_wait_s_);
        pairer_->release([this](double stamp, Scan&& s, std::optional<convert::OdometryData>&& o) {
            if (o) {
                s.odometry = OdometryInput{o->T_parent_child, segment_at(stamp)};
                s.velocity << o->linear_velocity, o->angular_velocity;
            }
            submit(std::move(s));
        });
    }

    // The odometry segment of a scan: the one its newest restart up to the scan started.
    std::uint32_t segment_at(double stamp) const {
        std::uint32_t segment = 0;
        for (const auto& [restart, number] : restarts_)
            if (restart <= stamp + kSameStamp) segment = std::max(segment, number);
        return segment;
    }

    // The odometry's status lines: restarts (a new segment), and scans it has no pose for.
    void on_status(const msg::Status& m) {
        const convert::StatusData s = convert::from_msg(m);
        if (s.component == ctx_.name()) return;
        const double stamp = convert::to_seconds(s.stamp);
        if (s.code == StatusCode::kRestarted) {
            restarts_.emplace_back(stamp, s.segment);
        } else if (common::says_no_pose(s.code)) {  // lost, skipped, rejected, bad cloud
            pairer_->add_no_pose(stamp);
            pair();
        }
    }

    void on_initial_pose(const msg::PoseWithCovarianceStamped& m) {
        const double stamp = convert::to_seconds(m.header.stamp);
        const std::string frame = convert::to_string(m.header.frame_id);
        if (map_state_ == kFailed) {
            event(StatusLevel::kError, StatusCode::kInitialPoseRefused,
                  "initial pose ignored: " + no_map_, stamp);
            return;
        }
        if (!frame.empty() && frame != frame_id_) {
            event(
                StatusLevel::kWarn, StatusCode::kInitialPoseRefused,
                "initial pose in frame '" + frame + "' ignored: it must be in '" + frame_id_ + "'",
                stamp);
            return;
        }
        const PoseHint hint = hint_from_msg(m, hint_radius_);
        if (!hint.T_map_lidar.matrix().allFinite()) {
            event(StatusLevel::kWarn, StatusCode::kInitialPoseRefused,
                  "initial pose ignored: not finite", stamp);
            return;
        }
        worker_->set_latest(hint);  // with the next scan, or alone
        const Eigen::Vector3d t = hint.T_map_lidar.translation();
        const Eigen::Vector3d x = hint.T_map_lidar.linear().col(0);
        char text[200];
        std::snprintf(text, sizeof text,
                      "initial pose accepted: (%.2f, %.2f) m, yaw %.1f deg; global localisation "
                      "searches within %.1f m of it",
                      t.x(), t.y(), std::atan2(x.y(), x.x()) * 180.0 / M_PI, hint.radius);
        event(StatusLevel::kOk, StatusCode::kInitialPose, text, stamp);
    }

    // Hands a scan to the worker (see the file comment for the policy): live, it replaces the one
    // waiting; offline, the component's thread waits until it is localised.
    void submit(Scan&& scan) {
        worker_->push(std::move(scan));
        if (!skip_while_busy_) worker_->wait_idle();
    }

    StatusCounters counters() {
        StatusCounters c;
        {
            std::lock_guard<std::mutex> lock(mutex_);
            c = counters_;
        }
        c.skipped_scans = std::uint32_t(worker_->skipped());
        return c;
    }

    // --- the worker thread: the localiser and the outputs ---

    // The newest initial pose (if one came), then the next scan (if one waits).
    void work(Worker::Step& step) {
        const std::optional<Scan>& scan = step.item;
        try {
            if (step.latest && localiser_) localiser_->set_initial_pose(*step.latest);
            if (scan) process(*scan);
        } catch (const std::exception& e) {
            // The localiser does not throw on data; whatever did is said, not fatal.
            event(StatusLevel::kError, StatusCode::kLocalisationFailed, common::one_line(e.what()),
                  scan ? scan->cloud.stamp : 0.0);
        }
    }

    // A new site: the SLAM's pose of a scan is its map pose (state OFF_MAP: not registered to a
    // saved map; the map is the one being made).
    void on_slam_pose(const msg::Odometry& m) {
        if (!new_site_) return;
        const convert::OdometryData o = convert::from_msg(m);
        if (!o.frame_id.empty() && o.frame_id != frame_id_) return;
        LocalisationUpdate u;
        u.stamp = convert::to_seconds(o.stamp);
        u.state = LocalisationState::kOffMap;
        u.pose_valid = true;
        u.T_map_lidar = o.T_parent_child;
        u.covariance = o.pose_covariance;
        u.message = "new site: the pose of the map being made (SLAM)";
        ++valid_;
        status_out_.publish(*status_msg(u, counters(), frame_id_));
        pose_out_.publish(*pose_msg(u, frame_id_));
        if (T_site_map_) publish_site_pose(u);
    }

    // The pose in the site's own frame (SITE/anchor.yaml): T_site_lidar = T_site_map T_map_lidar,
    // the covariance's translation and rotation blocks turned into the site frame.
    void publish_site_pose(const LocalisationUpdate& u) {
        auto m = pose_msg(u, "site");
        m->pose.pose = convert::to_pose(*T_site_map_ * u.T_map_lidar);
        registration::Matrix6d R = registration::Matrix6d::Zero();
        R.topLeftCorner<3, 3>() = T_site_map_->rotation();
        R.bottomRightCorner<3, 3>() = T_site_map_->rotation();
        convert::to_array36(R * u.covariance * R.transpose(), m->pose.covariance);
        site_pose_out_.publish(*m);
    }

    // Said once in the log (when loading failed), and on `status` every kNoMapRepeat scans for
    // whoever listens now.
    void publish_no_map(double stamp) {
        if (no_map_scans_++ % kNoMapRepeat == 0)
            publish_event(StatusLevel::kError, StatusCode::kNoMap, no_map_, stamp);
        status_out_.publish(*status_msg(stamp, no_map_, counters(), frame_id_));
    }

    void process(const Scan& scan) {
        if (!localiser_) {
            publish_no_map(scan.cloud.stamp);
            return;
        }
        preprocessor_->run(scan.cloud, scan.odometry ? &scan.velocity : nullptr, &preprocessed_);
        const LocalisationUpdate u =
            localiser_->process(scan.cloud.stamp, preprocessed_.map_points, scan.odometry);
        ++processed_;
        {
            std::lock_guard<std::mutex> lock(mutex_);
            counters_.relocalisations += u.state == LocalisationState::kRelocalised && u.global_ran;
        }
        const StatusCounters c = counters();
        status_out_.publish(*status_msg(u, c, frame_id_));
        if (u.pose_valid) {
            ++valid_;
            pose_out_.publish(*pose_msg(u, frame_id_));
            if (T_site_map_) publish_site_pose(u);
            if (scan.odometry)
                correction_out_.publish(*convert::to_msg(convert::TransformData{
                    convert::to_time(u.stamp), frame_id_, odom_frame(), u.T_map_odom}));
        }
        report_change(scan.index, u);
        last_state_ = u.state;
    }

    // The state changes an operator wants to hear about, on `status` and in the log.
    void report_change(std::uint64_t index, const LocalisationUpdate& u) {
        const std::string what = "scan " + std::to_string(index) + ": " + u.message;
        const bool changed = u.state != last_state_;
        if (u.state == LocalisationState::kRelocalised && u.global_ran) {
            const Eigen::Vector3d t = u.T_map_lidar.translation();
            char where[120];
            std::snprintf(where, sizeof where, " (at %.2f %.2f %.2f, confidence %.2f)", t.x(),
                          t.y(), t.z(), u.confidence);
            event(StatusLevel::kOk, StatusCode::kRelocalised, what + where, u.stamp);
        } else if (changed && u.state == LocalisationState::kLost) {
            event(StatusLevel::kWarn, StatusCode::kLost, what, u.stamp);
        } else if (changed && u.state == LocalisationState::kOffMap) {
            event(StatusLevel::kWarn, StatusCode::kOffMap, what, u.stamp);
        } else if (changed && u.state == LocalisationState::kTracking &&
                   last_state_ == LocalisationState::kOffMap) {
            event(StatusLevel::kOk, StatusCode::kOnMap, what, u.stamp);
        }
    }

    std::string odom_frame() {
        std::lock_guard<std::mutex> lock(mutex_);
        return odom_frame_;
    }

    // Thread-safe: the publisher and the logger are.
    void event(StatusLevel level, StatusCode code, const std::string& text, double stamp) {
        convert::log_status(ctx_.log(), level, text);
        publish_event(level, code, text, stamp);
    }

    void publish_event(StatusLevel level, StatusCode code, const std::string& text, double stamp) {
        events_out_.publish(*convert::to_msg(convert::StatusData{convert::to_time(stamp), frame_id_,
                                                                 ctx_.name(), level, code, text}));
    }

    runtime::ComponentContext& ctx_;
    std::string frame_id_;
    bool skip_while_busy_ = true;
    double odometry_wait_s_ = 1.0;
    HintRadius hint_radius_;
    common::SensorPreset preset_ = common::SensorPreset::kHdl64;
    LocaliserConfig config_;
    std::string map_dir_;
    enum MapState : int { kLoading, kReady, kFailed };
    std::atomic<int> map_state_{kLoading};
    bool on_site_ = false, new_site_ = false;  // site_dir given; and it has no version yet
    std::string no_map_;  // why there is no map (set before map_state_ turns kFailed)
    std::atomic<std::uint64_t> no_map_scans_{0};

    // The component's thread.
    std::optional<runtime::StampPairer<Scan, convert::OdometryData>> pairer_;
    std::vector<std::pair<double, std::uint32_t>> restarts_;  // the odometry's: stamp, segment
    double newest_scan_ = -1e300;
    std::string odom_frame_seen_;
    std::uint64_t scans_ = 0;

    // Shared with the worker (under mutex_).
    std::mutex mutex_;
    StatusCounters counters_;  // but skipped_scans: the worker's count
    std::string odom_frame_ = "odom";

    // The worker's.
    std::unique_ptr<Localiser> localiser_;
    std::optional<registration::Preprocessor> preprocessor_;
    registration::PreprocessedScan preprocessed_;
    LocalisationState last_state_ = LocalisationState::kInitialising;
    std::uint64_t processed_ = 0, valid_ = 0;

    runtime::Publisher<msg::LocalisationStatus> status_out_;
    runtime::Publisher<msg::PoseWithCovarianceStamped> pose_out_;
    std::optional<Eigen::Isometry3d> T_site_map_;  // the site's anchor, when it has one
    runtime::Publisher<msg::PoseWithCovarianceStamped> site_pose_out_;
    runtime::Publisher<msg::TransformStamped> correction_out_;
    runtime::Publisher<msg::Status> events_out_;
    std::optional<Worker> worker_;  // last: stopped before the members it uses go
};

}  // namespace
}  // namespace ltm::localisation

LTM_REGISTER_COMPONENT(
    ltm::localisation::LocalisationComponent, "localisation",
    "localisation on a saved map: PointCloud2 and odometry in; pose, map_to_odom and state out")
