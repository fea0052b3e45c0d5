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
// With global_thread (default: as skip_while_busy, i.e. live), a global localisation does not run
// on that worker: the localiser asks it (core/global_query.hpp) and a thread of its own
// (`localisation/global`) answers, one query at a time, while the worker goes on tracking the
// scans (or says "searching", no pose, while it has no fix); the answer is applied to the next
// scan, carried forward by the odometry. Without it (offline) the query runs on the scan itself.
//
// A large map takes seconds to load (a core's worth: 1.6 s for site_loop's 47 local maps). By
// default (`map_load: start`) it is loaded when the component is configured: the host runs nothing
// before it is ready, so the load never shares a second with the scans' work (issue 28: live, the
// load on the worker met the odometry's, maintenance's and mapping's first scans, the robot's worst
// 1 s window at start). `map_load: worker` (live only): the worker loads it when the component
// starts, the other components do not wait for it, and the newest scan waits for it. A missing or
// damaged map does not stop the host: the component stays up, says why in one line (log, `status`,
// and every scan's `localisation_status`) and localises nothing.
//
// Following a site (`site_poll_s` > 0, the split robot: its site_receiver commits the base
// station's versions into the robot's site while it runs): a thread of its own looks for a newer
// intact version every site_poll_s, loads it and builds its localiser while the worker goes on on
// the old map; the worker swaps it in between two scans, the new localiser taking the old one's
// track (the map frame stays put from version to version), so the poses go on without a gap or a
// global localisation. A session that started with no map at all (a new site) starts localising
// on the first version that arrives.
//
// A new site (no version yet): the pose of the map being made, OFF_MAP, never localised
// (`new_site_pose`, core/new_site_pose.hpp): by default each odometry pose under the mapping's
// map_to_odom (`slam_map_to_odom`), so the mapping's thread never delays a pose; on the split robot
// (`odometry`: no SLAM on it) the same under the base station's map_to_odom, only while the base
// station's mapping says it belongs to no version (`slam_map_version`, "": a new site there too)
// and no version is offered (`site/offer`); otherwise only the status goes out ("no map yet ...").
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <thread>

#include "common/core/cpu_budget.hpp"
#include "common/core/cpu_pacer.hpp"
#include "common/core/one_line.hpp"
#include "common/core/thread_clock.hpp"
#include "localisation/component/global_answers.hpp"
#include "localisation/component/loaded_localiser.hpp"
#include "localisation/component/localisation_messages.hpp"
#include "localisation/component/localiser_params.hpp"
#include "localisation/component/scan_pairing.hpp"
#include "localisation/component/scan_sensor.hpp"
#include "localisation/component/site_start.hpp"
#include "localisation/component/version_handoff.hpp"
#include "localisation/component/version_loader.hpp"
#include "localisation/core/new_site_pose.hpp"
#include "registration/core/preprocess.hpp"
#include "runtime/component.hpp"
#include "runtime/convert/dds_string.hpp"
#include "runtime/convert/geometry.hpp"
#include "runtime/convert/odometry.hpp"
#include "runtime/convert/pointcloud2.hpp"
#include "runtime/convert/status.hpp"
#include "runtime/convert/transform.hpp"
#include "runtime/link_messages.hpp"
#include "runtime/worker.hpp"

namespace ltm::localisation {
namespace {

using common::StatusCode;
using convert::StatusLevel;
using runtime::PathCheck;
using runtime::StopToken;
using runtime::TopicRole;

constexpr std::uint64_t kNoMapRepeat = 100;  // the no-map line again on `status` every N scans

using Worker = runtime::Worker<Scan, PoseHint>;
using GlobalWorker = runtime::Worker<GlobalRequest>;

class LocalisationComponent : public runtime::Component {
  public:
    explicit LocalisationComponent(runtime::ComponentContext& ctx) : ctx_(ctx) {
        auto& p = ctx.params();
        frame_id_ = p.get<std::string>("frame_id", "map");
        skip_while_busy_ = p.get<bool>("skip_while_busy", true);
        global_thread_ = p.get<bool>("global_thread", skip_while_busy_);
        // Issue 28: the global queries (on their thread) charged to the process's background CPU
        // budget (common/core/cpu_budget.hpp, declared by the maintenance's or the mapping's
        // `cpu_budget`): a query waits while it is in debt (at most kGlobalWaitMax), and the
        // paced workers wait for what a query used. Tracking is never paced.
        global_budget_ = p.get<std::string>("global_cpu_budget", "");
        if (!global_budget_.empty() && !global_thread_)
            p.fail("global_cpu_budget", "needs global_thread (the queries on their own thread)");
        odometry_wait_s_ = p.get<double>("odometry_wait_s", 1.0);
        if (!(odometry_wait_s_ >= 0)) p.fail("odometry_wait_s", "must be >= 0 (0: do not wait)");
        hint_radius_.sigmas = p.get<double>("initial_pose.sigmas", hint_radius_.sigmas);
        hint_radius_.min_radius = p.get<double>("initial_pose.min_radius", hint_radius_.min_radius);
        if (!(hint_radius_.sigmas > 0)) p.fail("initial_pose.sigmas", "must be > 0");
        if (!(hint_radius_.min_radius > 0)) p.fail("initial_pose.min_radius", "must be > 0");
        sensor_.emplace(ctx);
        preset_ = sensor_->preset();
        config_ = sensor_->config();
        map_dir_ = p.path("map", "", PathCheck::kNone);
        site_poll_s_ = p.get<double>("site_poll_s", 0.0);
        if (!(site_poll_s_ >= 0)) p.fail("site_poll_s", "must be >= 0 (0: the start version only)");
        const std::string pose_from = p.get<std::string>("new_site_pose", "slam_map_to_odom");
        const std::optional<NewSitePoseSource> source = parse_new_site_pose(pose_from);
        if (!source)
            p.fail("new_site_pose", std::string(kNewSitePoseNames) + ", not '" + pose_from + "'");
        new_site_pose_.emplace(*source);
        resolve_site_map(p);
        page_radius_on_site_ = on_site_ && !p.has("neighbourhood.radius");
        page_above_on_site_ = on_site_ && !p.has("neighbourhood.page_above_mb");
        page_on_site(&config_);
        if (site_poll_s_ > 0 && !on_site_) p.fail("site_poll_s", "needs site_dir");
        if (map_dir_.empty() && map_state_ != kFailed)
            p.fail("map", "required: the saved map directory to localise on (map_dir of mapping)");
        const std::string map_load = p.get<std::string>("map_load", "start");
        if (map_load != "start" && map_load != "worker")
            p.fail("map_load", "start or worker, not '" + map_load + "'");
        if (map_load == "worker" && !skip_while_busy_)
            p.fail("map_load", "worker needs skip_while_busy (offline, every scan waits anyway)");
        pairing_.emplace(odometry_wait_s_);
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

        // One global query at a time; a newer request (none while one runs: the localiser asks
        // only then) would replace a waiting one. A stop abandons the query.
        if (global_thread_)
            global_.emplace(
                runtime::WorkerOptions{ctx.name(), "global", 1, runtime::BusyPolicy::kDropOldest,
                                       runtime::StopPolicy::kAbandon},
                [this](GlobalWorker::Step& step, const StopToken&) { answer_query(*step.item); },
                [this](const std::string& what) {
                    event(StatusLevel::kError, StatusCode::kLocalisationFailed,
                          common::one_line(what), 0.0);
                });
        // Loaded at the start after the global thread exists: the localiser asks its queries there
        // (a map loaded before it ran every global query on the tracking worker, in one piece).
        if (map_load == "start" && map_state_ == kLoading) load_map();
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
            if (!new_site_pose_->composes_odometry())
                ctx.subscribe<msg::Odometry>("slam_odometry", TopicRole::kState,
                                             [this](const msg::Odometry& m) { on_slam_pose(m); });
            ctx.subscribe<msg::TransformStamped>(
                "slam_map_to_odom", TopicRole::kState, [this](const msg::TransformStamped& m) {
                    if (!new_site_) return;
                    for (const LocalisationUpdate& u :
                         new_site_pose_->map_to_odom(convert::to_isometry(m.transform)))
                        publish_new_site(u);
                    if (new_site_pose_->frame_is_ours()) correction_out_.publish(m);
                });
            if (new_site_pose_->source() == NewSitePoseSource::kBaseStation) {
                ctx.subscribe<msg::SiteOffer>(
                    "site/offer", TopicRole::kMap,
                    [this](const msg::SiteOffer&) { new_site_pose_->offered(); });
                ctx.subscribe<msg::MapVersion>(
                    "slam_map_version", TopicRole::kMap, [this](const msg::MapVersion& m) {
                        new_site_pose_->base_version(convert::to_string(m.version));
                    });
            }
        }
        if (site_poll_s_ > 0) {
            loader_.emplace(
                site_dir_, in_use_, site_poll_s_, localisation_map_preset(preset_), config_,
                [this](bool warning, const std::string& line) {
                    if (warning) {
                        ctx_.log().warn(line);
                    } else {
                        ctx_.log().error(line);
                    }
                },
                global_thread_);
            // A look every site_poll_s; a finished load is taken within 0.1 s.
            ctx.add_timer(std::min(0.1, site_poll_s_), [this] { follow_site(); });
        }
        // Scans whose odometry is late: looked at a few times within odometry_wait_s.
        if (odometry_wait_s_ > 0)
            ctx.add_timer(std::max(0.02, odometry_wait_s_ / 4), [this] { pair(); });
    }

    ~LocalisationComponent() override {
        if (worker_) worker_->stop();
        if (global_) global_->stop();
    }

    void on_activate() override {
        if (global_) global_->start();
        // Live, the map is the worker's first job.
        worker_->start([this](const StopToken&) {
            if (map_state_ == kLoading) load_map();
        });
    }

    void on_shutdown() override {
        // Scans still waiting for their odometry go without it.
        if (worker_->started()) pairing_->release_all([this](Scan&& s) { submit(std::move(s)); });
        worker_->stop(ctx_.work_deadline());
        if (global_) global_->stop();
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
        site_dir_ = site;
        if (!map_dir_.empty()) p.fail("map", "give either map or site_dir, not both");
        const SiteStart start = resolve_site_start(p, site, version);
        for (const std::string& note : start.notes) ctx_.log().warn(note);
        if (start.T_site_map) {
            T_site_map_ = start.T_site_map;
            site_pose_out_ =
                ctx_.advertise<msg::PoseWithCovarianceStamped>("site_pose", TopicRole::kState);
            ctx_.log().info("site " + site + ": anchored (" + start.anchor_file +
                            "): the pose in frame `site` on site_pose too");
        }
        if (!start.map_dir.empty()) {
            map_dir_ = start.map_dir;
            in_use_ = start.in_use;
            ctx_.log().info("site " + site + ": localising on " + start.describe);
            return;
        }
        new_site_ = true;
        no_map_ = new_site_pose_->start_line();
        if (site_poll_s_ > 0) no_map_ += "; a version that arrives is localised on at once";
        ctx_.log().info("site " + site + ": " + no_map_);
        map_state_ = kFailed;
    }

    // The worker's first job: the map, or why there is none (no_map_): the component then runs
    // and localises nothing.
    void load_map() {
        ctx_.log().info("loading the map " + map_dir_);
        LoadedLocaliser l;
        try {
            l = load_localiser(map_dir_, localisation_map_preset(preset_), config_,
                               global_.has_value());
        } catch (const std::exception& e) {
            no_map_ = "no map to localise on: " + common::one_line(e.what());
            ctx_.log().error(no_map_ + " (the component runs and localises nothing)");
            map_state_ = kFailed;
            return;
        }
        for (const std::string& r : l.refused) ctx_.log().warn("map: " + r + " (left out)");
        localiser_ = std::move(l.localiser);
        if (l.global) answers_.use(std::move(l.global));
        map_state_ = kReady;
        ctx_.log().info(l.line());
    }

    // --- the component's thread: inputs, pairing ---

    void on_points(const msg::PointCloud2& m) {
        const std::uint64_t index = scans_++;
        // Under auto, every scan until one tells the sensor (a new site's too: the versions that
        // arrive later are loaded with its settings).
        const bool go_on = !new_site_ && map_state_ != kFailed;
        if (!go_on && sensor_->ready()) {
            // A new site: the SLAM's poses are published as they come (on_slam_pose).
            if (!new_site_) publish_no_map(convert::to_seconds(m.header.stamp));
            return;
        }
        Scan scan;
        scan.index = index;
        const std::string err = convert::from_pointcloud2(m, scan.cloud);
        if (!go_on) {
            if (err.empty()) sensor_known(scan.cloud);
            if (!new_site_) publish_no_map(convert::to_seconds(m.header.stamp));
            return;
        }
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
        if (!sensor_->ready() && !sensor_known(scan.cloud)) return;  // the next scan decides
        newest_scan_ = scan.cloud.stamp;
        pairing_->add_scan(std::move(scan));
        pair();
    }

    // A preset `auto` that no name told: the scans' preprocessing made on the first scan that
    // tells the sensor (before any scan reaches the worker). A narrow one's: the localiser's and
    // the map's settings become the narrow preset's (the worker reloads the map with them before
    // its first scan, and the site's versions are loaded with them).
    bool sensor_known(const common::PointCloud& cloud) {
        std::optional<ScanSensor::Retune> retune;
        if (!sensor_->add(cloud, &retune)) return false;
        if (!retune) return true;
        page_on_site(&retune->config);
        if (loader_) loader_->retune(localisation_map_preset(retune->preset), retune->config);
        std::lock_guard<std::mutex> lock(mutex_);
        retune_ = std::move(retune);
        return true;
    }

    // The worker, before a scan: the settings the scans told (sensor_known), the map in use
    // loaded again with them (no scan was localised yet: the detection comes first).
    void apply_retune() {
        std::optional<ScanSensor::Retune> retune;
        {
            std::lock_guard<std::mutex> lock(mutex_);
            retune.swap(retune_);
        }
        if (!retune) return;
        preset_ = retune->preset;
        config_ = retune->config;
        if (map_state_ == kReady && !map_dir_.empty()) load_map();
    }

    // On a site (its versions never change once written) a large map is paged unless the launch
    // config says otherwise (`neighbourhood.*`; core/neighbourhood_builder.hpp); a `map`
    // directory may be one a mapping component is writing, so there it is whole unless asked.
    void page_on_site(LocaliserConfig* config) const {
        if (page_radius_on_site_) config->neighbourhood.radius = kSiteNeighbourhoodRadius;
        if (page_above_on_site_) config->neighbourhood.page_above_mb = kSitePageAboveMb;
    }

    void on_odometry(const msg::Odometry& m) {
        convert::OdometryData o = convert::from_msg(m);
        if (!o.frame_id.empty() && o.frame_id != odom_frame_seen_) {
            odom_frame_seen_ = o.frame_id;
            std::lock_guard<std::mutex> lock(mutex_);
            odom_frame_ = o.frame_id;
        }
        const double stamp = convert::to_seconds(o.stamp);
        if (new_site_ && new_site_pose_->composes_odometry()) {
            if (const std::optional<LocalisationUpdate> u =
                    new_site_pose_->odometry({stamp, o.T_parent_child, o.pose_covariance}))
                publish_new_site(*u);
            return;
        }
        pairing_->add_pose(std::move(o));
        pair();
    }

    // A new site (core/new_site_pose.hpp): the pose of the map being made, or (the split robot,
    // while the base station's map_to_odom is not this session's) a status line without one.
    void publish_new_site(const LocalisationUpdate& u) {
        const bool split = new_site_pose_->source() == NewSitePoseSource::kBaseStation;
        if (split && no_map_scans_++ % kNoMapRepeat == 0)
            publish_event(StatusLevel::kWarn, StatusCode::kNoMap, u.message, u.stamp);
        if (u.message != new_site_said_) ctx_.log().info(new_site_said_ = u.message);
        status_out_.publish(*status_msg(u, counters(), frame_id_));
        if (!u.pose_valid) return;
        ++valid_;
        pose_out_.publish(*pose_msg(u, frame_id_));
        if (T_site_map_) publish_site_pose(u);
    }

    // --- following the site (site_poll_s) ---

    // The component's thread: a newer version, loaded (version_loader.hpp), is handed to the
    // worker, which swaps it in before its next scan; a new site's session localises from then on.
    void follow_site() {
        std::optional<VersionLoader::Loaded> n = loader_->poll();
        if (!n) return;
        char text[300];
        std::snprintf(text, sizeof text, "site %s: %s arrived (loaded in %.2f s): localising on it",
                      site_dir_.c_str(), n->version.name.c_str(), n->load_s);
        handoff_.offer(std::move(*n));
        event(StatusLevel::kOk, StatusCode::kOnMap, text, newest_scan_ > 0 ? newest_scan_ : 0.0);
        if (map_state_ != kReady) {
            no_map_.clear();
            map_state_ = kReady;
        }
        new_site_ = false;
    }

    // The worker, before a scan: a newer version's localiser takes over the running one's track.
    void swap_in_pending() {
        std::optional<VersionLoader::Loaded> next = handoff_.take();
        if (!next) return;
        map_dir_ = next->version.map_dir();  // the map a retune loads again
        // The version's global localiser answers the next query (one out on the old map finishes
        // there: the old one lives until then, and its answer holds in the same map frame).
        if (next->global) answers_.use(std::move(next->global));
        if (localiser_) next->localiser->take_track(*localiser_);
        localiser_ = std::move(next->localiser);
        ctx_.log().info("now on " + next->version.name + " (" + to_string(localiser_->state()) +
                        ")");
    }

    // Hands on every waiting scan whose odometry came (with its pose and twist), or will not come
    // (see the file comment).
    void pair() {
        pairing_->release(ctx_.matched_publishers("odometry") > 0,
                          [this](Scan&& s) { submit(std::move(s)); });
    }

    // The odometry's status lines: restarts (a new segment), and scans it has no pose for.
    void on_status(const msg::Status& m) {
        const convert::StatusData s = convert::from_msg(m);
        if (s.component == ctx_.name()) return;
        if (pairing_->status(s)) pair();
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
            swap_in_pending();
            apply_retune();
            if (step.latest && localiser_) localiser_->set_initial_pose(*step.latest);
            if (scan) process(*scan);
        } catch (const std::exception& e) {
            // The localiser does not throw on data; whatever did is said, not fatal.
            event(StatusLevel::kError, StatusCode::kLocalisationFailed, common::one_line(e.what()),
                  scan ? scan->cloud.stamp : 0.0);
        }
    }

    // --- the global thread ---

    // One query, its answer left for the worker's next scan; the log line with its wall-clock
    // span (`./ltm bench budget` sets the poses published meanwhile against it). With
    // global_cpu_budget it waits for the budget first and is charged to it.
    void answer_query(const GlobalRequest& request) {
        const double t0 = GlobalAnswers::wall_clock_s();
        pace_query();
        const double cpu0 = common::thread_cpu_s();
        const std::string line = answers_.answer(request, t0);
        if (global_pacer_)
            global_pacer_->wait_after(global_cpu_s_ += common::thread_cpu_s() - cpu0,
                                      common::steady_wall_s());
        ctx_.log().info(line);
    }

    // global_cpu_budget: joins the budget at the first query (the components declaring it are all
    // configured by then) and waits while it is in debt, at most kGlobalWaitMax.
    void pace_query() {
        if (global_budget_.empty()) return;
        if (!global_pacer_) {
            std::string error;
            auto budget = common::shared_cpu_budget(global_budget_, 0.0, 0.0, &error);
            if (!budget) {
                ctx_.log().warn("global_cpu_budget: " + error + ": the queries are not paced");
                global_budget_.clear();
                return;
            }
            global_pacer_.emplace(std::move(budget));
            global_pacer_->wait_after(0.0, common::steady_wall_s());
        }
        const double wait =
            std::min(global_pacer_->wait_now(common::steady_wall_s()), kGlobalWaitMax);
        if (wait > 0.0) std::this_thread::sleep_for(std::chrono::duration<double>(wait));
    }

    // A new site: the SLAM's pose of a scan is its map pose (state OFF_MAP: not registered to a
    // saved map; the map is the one being made).
    void on_slam_pose(const msg::Odometry& m) {
        if (!new_site_) return;
        const convert::OdometryData o = convert::from_msg(m);
        if (!o.frame_id.empty() && o.frame_id != frame_id_) return;
        publish_new_site(NewSitePose::slam_pose(convert::to_seconds(o.stamp), o.T_parent_child,
                                                o.pose_covariance));
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

    // What the localiser holds, for the host's minute memory line: at most every
    // kMemoryReportPeriod seconds, from the worker (which owns the localiser).
    void report_memory() {
        const double now = common::steady_wall_s();
        if (now < next_memory_report_) return;
        next_memory_report_ = now + runtime::kMemoryReportPeriod;
        ctx_.report_memory("map", localiser_->map().memory_bytes());
        const auto& n = localiser_->neighbourhood();
        ctx_.report_memory("neighbourhood",
                           n && n->current() ? n->current()->memory_bytes() : std::size_t(0));
    }

    void process(const Scan& scan) {
        if (!localiser_) {
            publish_no_map(scan.cloud.stamp);
            return;
        }
        sensor_->preprocessor().run(scan.cloud, scan.odometry ? &scan.velocity : nullptr,
                                    &preprocessed_);
        if (global_) answers_.give(*localiser_);
        const LocalisationUpdate u =
            localiser_->process(scan.cloud.stamp, preprocessed_.map_points, scan.odometry);
        if (global_)
            if (std::optional<GlobalRequest> r = localiser_->take_request())
                global_->push(std::move(*r));
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
        report_memory();
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
    bool global_thread_ = true;  // global localisation on `localisation/global`
    double odometry_wait_s_ = 1.0;
    HintRadius hint_radius_;
    common::SensorPreset preset_ = common::SensorPreset::kHdl64;  // the settings' (auto: spinning)
    std::optional<ScanSensor> sensor_;  // the component's thread (its preprocessor: the worker's)
    LocaliserConfig config_;
    std::string map_dir_;
    enum MapState : int { kLoading, kReady, kFailed };
    std::atomic<int> map_state_{kLoading};
    bool on_site_ = false;                      // site_dir given
    bool page_radius_on_site_ = false;          // on a site, neighbourhood.radius not given
    bool page_above_on_site_ = false;           // on a site, neighbourhood.page_above_mb not given
    std::atomic<bool> new_site_{false};         // and it has no version yet (until one arrives)
    std::optional<NewSitePose> new_site_pose_;  // new_site_pose (component thread)
    std::string new_site_said_;  // the last reason logged (once each time it changes)
    std::string site_dir_;
    std::uint32_t in_use_ = 0;  // the version localised on (0: none)
    double site_poll_s_ = 0.0;
    std::optional<VersionLoader> loader_;  // site_poll_s: its thread waited for at destruction
    std::string no_map_;  // why there is no map (set before map_state_ turns kFailed)
    std::atomic<std::uint64_t> no_map_scans_{0};

    // The component's thread.
    std::optional<ScanPairing> pairing_;  // scans with their odometry poses
    double newest_scan_ = -1e300;
    std::string odom_frame_seen_;
    std::uint64_t scans_ = 0;

    // Shared with the worker (under mutex_).
    std::mutex mutex_;
    std::optional<ScanSensor::Retune> retune_;  // the scans told a narrow sensor (auto)
    StatusCounters counters_;                   // but skipped_scans: the worker's count
    std::string odom_frame_ = "odom";

    // The worker's.
    std::unique_ptr<Localiser> localiser_;
    registration::PreprocessedScan preprocessed_;
    LocalisationState last_state_ = LocalisationState::kInitialising;
    std::uint64_t processed_ = 0, valid_ = 0;

    runtime::Publisher<msg::LocalisationStatus> status_out_;
    runtime::Publisher<msg::PoseWithCovarianceStamped> pose_out_;
    std::optional<Eigen::Isometry3d> T_site_map_;  // the site's anchor, when it has one
    runtime::Publisher<msg::PoseWithCovarianceStamped> site_pose_out_;
    runtime::Publisher<msg::TransformStamped> correction_out_;
    runtime::Publisher<msg::Status> events_out_;
    double next_memory_report_ = 0.0;  // steady wall time [s] (report_memory)
    // The global thread's global localiser (the worker swaps a newer version's in) and its answer
    // for the worker.
    GlobalAnswers answers_;
    VersionHandoff handoff_;  // a newer site version, from the component's thread to the worker

    std::optional<GlobalWorker> global_;
    // global_cpu_budget (the global thread's).
    static constexpr double kGlobalWaitMax = 0.5;  // [s] a query waits for the budget at most
    std::string global_budget_;
    std::optional<common::CpuPacer> global_pacer_;
    double global_cpu_s_ = 0.0;
    std::optional<Worker> worker_;  // last: stopped before the members it uses go
};

}  // namespace
}  // namespace ltm::localisation

LTM_REGISTER_COMPONENT(
    ltm::localisation::LocalisationComponent, "localisation",
    "localisation on a saved map: PointCloud2 and odometry in; pose, map_to_odom and state out")
