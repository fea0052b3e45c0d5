// Map maintenance as a component: registered scans in (`points`, PointCloud2 in the sensor frame)
// with their world poses (by default nav_msgs/Odometry on `odometry`, remapped to the mapping's
// `corrected_odometry`; or a PoseStamped / PoseWithCovarianceStamped on `pose`: `input`), paired
// by stamp; out `map_changes` (ltm_msgs/MapChangeSet) for every maintenance pass that changed the
// map, and the state on the shared `status`. A LongTermMap (maintenance/core) takes the scans.
//
// Threads: the component's thread takes the inputs and pairs each scan with the pose of the same
// stamp (a scan waits for its pose until a newer pose says it has none); the long-term map lives
// on a worker thread of its own, which takes the paired scans in order, runs a pass every
// `maintain_every_s` seconds of scan time (stamps, so that a replay at any speed makes the same
// passes) and the last one at shutdown. At most `max_queue` scans wait for the worker: then the
// oldest is dropped (skip_while_busy, a live sensor) or the component's thread waits (offline:
// back-pressure on the sensor, nothing dropped). With `cpu_share` below 1 the worker spreads its
// work: after each scan, between the regions a scan's view pages in, judges and pages out, and
// between the regions of a pass and their steps, it waits as long as keeps its CPU time
// within that share of one core (common/core/cpu_pacer.hpp), so a pass of seconds becomes a
// slower pass at a bounded load instead of a burst; the scans wait in the queue meanwhile, and the
// decisions are the same (nothing enters the map during a pass). Not while shutting down. With
// `cpu_budget` the worker draws from a budget the process's other background work shares
// (common/core/cpu_budget.hpp: the mapping's clearing and saves), so that together they stay
// within cpu_share of one core; the log's last lines give the longest piece of work between two
// waits (what can pass the share in a second) and the time waited.
// The queue is bounded by its memory too (`max_queue_mb`, the scans as they wait, packed or not):
// a scan that would pass it does what one past max_queue does (live: the oldest waiting scan is
// dropped; offline: the component's thread waits for room); each time the queue fills, by either
// bound, the log says so (once until it has room again), and the last lines count the drops.
//
// With `map_file`, the maintained map is loaded from it when it exists (this run is the next
// session on it; a damaged file refuses the component with one line and stays as it is) and saved
// to it at shutdown (its folder created then). With `site_dir` instead (a lifelong session,
// map/core/site_store.hpp), it is loaded from the site's start version (`site_version`, or the
// newest intact one) and saved into the site's staging, which the `site` component commits. With
// `output_dir` (created when missing) every pass writes there its change record (changes_NNNN.ltmc,
// maintenance/core/change_record.hpp) and appends its summary to changes.txt; at the end of the
// session changes_removed_added.ply holds every change of the run (removed voxels red, added
// green), made from the records (the run's changes are not kept in memory: they grew with the
// day's length, issue 28).
// Paging (`paging_radius`, `paging_dir`): only the regions near the robot stay in memory, the
// others wait on disk (maintenance/core/region_pager.hpp; the worker reads them back when a scan
// or a view reaches them, on its own thread).
// Memory (issue 28): a scan that finds `pack_after` scans or more waiting (through a pass) is
// kept packed (maintenance/core/packed_scan.hpp: lossless, about 60 % of its 12 B a point on real
// scans) until the worker takes it; the log's last line gives the queue's peak in scans and MiB.
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>

#include "common/core/cpu_budget.hpp"
#include "common/core/cpu_pacer.hpp"
#include "common/core/io_error.hpp"
#include "common/core/one_line.hpp"
#include "common/core/thread_clock.hpp"
#include "maintenance/component/maintenance_params.hpp"
#include "maintenance/component/map_change_messages.hpp"
#include "maintenance/component/waiting_scans.hpp"
#include "maintenance/core/change_record.hpp"
#include "maintenance/core/change_report.hpp"
#include "maintenance/core/long_term_map.hpp"
#include "maintenance/core/packed_scan.hpp"
#include "map/core/site_staging.hpp"
#include "map/core/site_store.hpp"
#include "runtime/component.hpp"
#include "runtime/convert/dds_string.hpp"
#include "runtime/convert/geometry.hpp"
#include "runtime/convert/pointcloud2.hpp"
#include "runtime/convert/status.hpp"
#include "runtime/stamp_pairer.hpp"
#include "runtime/worker.hpp"

namespace ltm::maintenance {
namespace {

namespace fs = std::filesystem;
using common::StatusCode;
using convert::StatusLevel;
using runtime::TopicRole;

using runtime::StopToken;

constexpr double kSameStamp = 1e-4;      // a scan and its pose [s]
constexpr std::size_t kMaxPoses = 400;   // poses kept for pairing
constexpr std::size_t kMaxWaiting = 50;  // scans waiting for their pose
constexpr double kPaceBurst = 0.1;       // [s] of CPU the worker may use at once (cpu_share)
constexpr double kPaceSlice = 0.05;      // [s] a wait is cut into (a stop ends it)

struct Scan {
    double stamp = 0.0;
    std::vector<Eigen::Vector3f> points;  // sensor frame (empty when packed)
    std::optional<PackedScan> packed;     // the points, packed while they wait
    Eigen::Isometry3d T_world_sensor = Eigen::Isometry3d::Identity();

    std::size_t memory_bytes() const {
        return sizeof(Scan) + points.capacity() * sizeof(Eigen::Vector3f) +
               (packed ? packed->memory_bytes() : 0);
    }
    std::size_t unpacked_bytes() const {
        return sizeof(Scan) + (packed ? packed->count : points.size()) * sizeof(Eigen::Vector3f);
    }
};

using Points = std::vector<Eigen::Vector3f>;
using Worker = runtime::Worker<Scan>;

class MaintenanceComponent : public runtime::Component {
  public:
    explicit MaintenanceComponent(runtime::ComponentContext& ctx)
        : ctx_(ctx),
          config_(load_maintenance_params(ctx.params())),
          pairer_({kSameStamp, kMaxPoses, kMaxWaiting}),
          waiting_(std::size_t(config_.max_queue), std::size_t(config_.max_queue_mb * 1048576.0)),
          worker_(
              {ctx.name(), "work", std::size_t(config_.max_queue),
               config_.skip_while_busy ? runtime::BusyPolicy::kDropOldest
                                       : runtime::BusyPolicy::kBlock},
              [this](Worker::Step& step, const StopToken& stop) { work(*step.item, stop); },
              [this](const std::string& what) {
                  event(StatusLevel::kError, StatusCode::kMaintenanceFailed, common::one_line(what),
                        stamp_);
              }) {
        auto& p = ctx.params();
        if (!config_.cpu_budget.empty()) {
            std::string error;
            auto budget = common::shared_cpu_budget(config_.cpu_budget, config_.cpu_share,
                                                    kPaceBurst, &error);
            if (!budget) p.fail("cpu_budget", error);
            pacer_.emplace(std::move(budget));
        } else if (config_.cpu_share < 1.0) {
            pacer_.emplace(config_.cpu_share, kPaceBurst);
        }
        load_map(p);
        if (!config_.output_dir.empty()) {
            std::error_code ec;
            fs::create_directories(config_.output_dir, ec);
            if (ec || !fs::is_directory(config_.output_dir))
                p.fail("output_dir", "cannot create " + config_.output_dir + ": " +
                                         (ec ? ec.message() : "not a directory"));
            summary_.open(fs::path(config_.output_dir) / "changes.txt", std::ios::trunc);
            if (!summary_)
                p.fail("output_dir", "cannot write " + config_.output_dir + "/changes.txt");
        }
        // The scans waiting for their pose and for the worker, for the host's minute memory
        // line (the map's parts are reported after each pass).
        ctx.add_timer(runtime::kMemoryReportPeriod, [this] {
            ctx_.report_memory("pairing", pairer_.waiting_bytes([](const Points& p) {
                return p.capacity() * sizeof(Eigen::Vector3f);
            }));
            std::lock_guard<std::mutex> lock(queue_mutex_);
            ctx_.report_memory("queue", waiting_.bytes());
        });
        ctx.subscribe<msg::PointCloud2>("points", TopicRole::kSensor,
                                        [this](const msg::PointCloud2& m) { on_points(m); });
        switch (config_.input) {
            case PoseInput::kOdometry:
                ctx.subscribe<msg::Odometry>(
                    "odometry", TopicRole::kState, [this](const msg::Odometry& m) {
                        on_pose(convert::to_seconds(m.header.stamp),
                                convert::to_isometry(m.pose.pose), m.header.frame_id);
                    });
                break;
            case PoseInput::kPose:
                ctx.subscribe<msg::PoseStamped>(
                    "pose", TopicRole::kState, [this](const msg::PoseStamped& m) {
                        on_pose(convert::to_seconds(m.header.stamp), convert::to_isometry(m.pose),
                                m.header.frame_id);
                    });
                break;
            case PoseInput::kPoseWithCovariance:
                ctx.subscribe<msg::PoseWithCovarianceStamped>(
                    "pose", TopicRole::kState, [this](const msg::PoseWithCovarianceStamped& m) {
                        on_pose(convert::to_seconds(m.header.stamp),
                                convert::to_isometry(m.pose.pose), m.header.frame_id);
                    });
                break;
        }
        changes_out_ = ctx.advertise<msg::MapChangeSet>("map_changes", TopicRole::kMap);
        events_out_ = ctx.advertise<msg::Status>("status", TopicRole::kState);
    }

    ~MaintenanceComponent() override { worker_.stop(); }

    void on_activate() override { worker_.start(); }

    void on_shutdown() override {
        // Scans still waiting for their poses: those will not come now.
        pairer_.release_all(
            [this](double, Points&&, std::optional<Eigen::Isometry3d>&&) { ++no_pose_; });
        stopping_ = true;  // no pacing: what waits is finished at full speed
        room_cv_.notify_all();
        worker_.stop(ctx_.work_deadline());  // finishes the scans it has, within the deadline
        end_session();
        ctx_.log().info(std::to_string(scans_) + " scans: " + std::to_string(used_) +
                        " maintained, " + std::to_string(no_pose_ + pairer_.dropped()) +
                        " without a pose, " + std::to_string(worker_.skipped()) +
                        " dropped while busy" + spacing_note() + "; " + std::to_string(passes_) +
                        " passes");
        char queue[300];
        std::snprintf(queue, sizeof queue,
                      "queue: at most %zu scans waiting, %.1f MiB (%.1f MiB unpacked); %llu "
                      "scans packed; full %llu time(s) (max_queue %d, max_queue_mb %.0f): %llu "
                      "scans dropped for its memory, %.1f s waited for room",
                      waiting_.peak_count(), waiting_.peak_bytes() / 1048576.0,
                      waiting_.peak_unpacked_bytes() / 1048576.0,
                      static_cast<unsigned long long>(packed_),
                      static_cast<unsigned long long>(waiting_.full_times()), config_.max_queue,
                      config_.max_queue_mb, static_cast<unsigned long long>(dropped_for_bytes_),
                      waited_for_room_s_);
        ctx_.log().info(queue);
        if (pacer_) {
            char pace[200];
            std::snprintf(pace, sizeof pace,
                          "paced at %.2f of a core (%s): longest piece of work between two waits "
                          "%.0f ms of CPU, %.1f s waited in all",
                          pacer_->share(),
                          config_.cpu_budget.empty()
                              ? "its own budget"
                              : ("the budget '" + config_.cpu_budget + "'").c_str(),
                          pacer_->longest_piece_s() * 1e3, paced_wait_s_);
            ctx_.log().info(pace);
        }
    }

  private:
    // The saved map when there is one (a damaged one, or one of another lattice, refuses the
    // component: it would be overwritten at shutdown), else a new one; this run's session.
    void load_map(runtime::Parameters& p) {
        std::uint32_t session = 0;
        resolve_files(p);
        PagingConfig paging{config_.paging_radius, paging_dir()};
        try {  // the folder first: a map file's regions go there as they are read
            if (paging.radius > 0.0) RegionPager(paging.dir, config_.maintenance);
        } catch (const common::IoError& e) {
            p.fail("paging_dir", e.what());
        }
        if (!load_file_.empty() && fs::exists(load_file_)) {
            try {
                map_ = std::make_unique<LongTermMap>(
                    LongTermMap::load(load_file_, config_.maintenance, paging));
            } catch (const common::IoError& e) {
                p.fail(config_.site_dir.empty() ? "map_file" : "site_dir", e.what());
            }
            if (!map_->sessions().empty()) session = map_->sessions().back() + 1;
            const LongTermMapStats st = map_->stats();
            ctx_.log().info("map " + load_file_ + ": " + std::to_string(st.voxels) + " voxels of " +
                            std::to_string(map_->sessions().size()) + " sessions");
        } else {
            map_ = std::make_unique<LongTermMap>(config_.maintenance);
            map_->set_paging(paging);
        }
        if (paging.radius > 0.0)
            ctx_.log().info("paging: regions farther than " + std::to_string(int(paging.radius)) +
                            " m from the robot wait in " + paging.dir);
        session_ = config_.session >= 0 ? std::uint32_t(config_.session) : session;
    }

    std::string paging_dir() const {
        if (!config_.paging_dir.empty()) return config_.paging_dir;
        if (!config_.output_dir.empty()) return config_.output_dir + "/paged_regions";
        return (fs::temp_directory_path() /
                ("ltm-maintenance-" + std::to_string(::getpid()) + "-" + ctx_.name()))
            .string();
    }

    // Where the maintained map comes from and goes: map_file both ways, or with site_dir the
    // start version's file in and the site's staging out.
    void resolve_files(runtime::Parameters& p) {
        load_file_ = save_file_ = config_.map_file;
        if (config_.site_dir.empty()) return;
        // The staging is this session's before anything is saved into it
        // (map/core/site_staging.hpp): shared with the mapping and the site component.
        bool made = false;
        try {
            staging_claim_ = map::claim_staging(config_.site_dir, &made);
        } catch (const common::IoError& e) {
            p.fail("site_dir", e.what());
        }
        if (made && !staging_claim_->removed().empty()) ctx_.log().warn(staging_claim_->removed());
        map::SiteSession site;
        try {
            site = map::resolve_site(config_.site_dir, config_.site_version);
        } catch (const common::IoError& e) {
            p.fail(config_.site_version.empty() ? "site_dir" : "site_version", e.what());
        }
        for (const std::string& note : site.notes) ctx_.log().warn(note);
        save_file_ = site.staging_maintained_map_file;
        if (site.start && fs::exists(site.start->maintained_map_file())) {
            load_file_ = site.start->maintained_map_file();
        } else {
            ctx_.log().info("site " + config_.site_dir + ": " +
                            (site.start ? site.start->name + " has no maintained map"
                                        : std::string("a new site")) +
                            ": a new maintained map");
        }
    }

    // --- the component's thread: inputs, pairing ---

    void on_points(const msg::PointCloud2& m) {
        ++scans_;
        common::PointCloud cloud;
        const std::string err = convert::from_pointcloud2(m, cloud);
        if (!err.empty()) {
            event(StatusLevel::kError, StatusCode::kBadCloud, "scan ignored: " + err, cloud.stamp);
            return;
        }
        pairer_.add_scan(cloud.stamp, std::move(cloud.points));  // full: drops the oldest
        pair();
    }

    void on_pose(double stamp, const Eigen::Isometry3d& T, const char* frame_id) {
        if (!T.matrix().allFinite()) return;
        const std::string frame = convert::to_string(frame_id);
        if (!frame.empty()) {
            std::lock_guard<std::mutex> lock(mutex_);
            frame_id_ = frame;
        }
        pairer_.add_pose(stamp, T);
        pair();
    }

    // Hands on every waiting scan whose pose came, and drops those whose pose will not come.
    void pair() {
        pairer_.release([this](double stamp, Points&& points,
                               std::optional<Eigen::Isometry3d>&& T) {
            if (!T) {
                ++no_pose_;
                return;
            }
            if (!views_.take(stamp, *T)) return;  // too near the last scan taken
            Scan scan{stamp, std::move(points), std::nullopt, *T};
            if (config_.pack_after >= 0 && worker_.waiting() >= std::size_t(config_.pack_after)) {
                scan.packed = pack_points(scan.points);
                scan.points = Points();
                ++packed_;
            }
            if (worker_.waiting() >= std::size_t(config_.max_queue)) note_full("max_queue");
            make_room(scan.memory_bytes());
            count_in(scan);
            const std::uint64_t skipped = worker_.skipped();
            if (!worker_.push(std::move(scan))) {  // offline: waits for room
                count_out(false);
            } else if (worker_.skipped() > skipped) {
                count_out(true);  // the oldest was dropped (live)
            }
        });
    }

    // max_queue_mb: a scan that would take the waiting scans past it waits for room (offline) or
    // makes room by dropping the oldest (live).
    void make_room(std::size_t bytes) {
        std::unique_lock<std::mutex> lock(queue_mutex_);
        if (!waiting_.over_bytes(bytes)) return;
        note_full_locked("max_queue_mb");
        if (config_.skip_while_busy) {
            while (waiting_.over_bytes(bytes)) {
                lock.unlock();
                const bool dropped = worker_.drop_oldest();
                lock.lock();
                if (!dropped) break;  // the worker took it meanwhile
                waiting_.remove_front();
                ++dropped_for_bytes_;
            }
            return;
        }
        const double t0 = common::steady_wall_s();
        while (waiting_.over_bytes(bytes) && !stopping_)
            room_cv_.wait_for(lock, std::chrono::milliseconds(50));
        waited_for_room_s_ += common::steady_wall_s() - t0;
    }

    // The first time the queue is full since it last had room: one line (never silently).
    void note_full(const char* bound) {
        std::lock_guard<std::mutex> lock(queue_mutex_);
        note_full_locked(bound);
    }
    void note_full_locked(const char* bound) {
        if (!waiting_.mark_full()) return;
        char text[240];
        std::snprintf(text, sizeof text,
                      "queue full (%s: %zu scans waiting, %.1f MiB; max_queue %d, max_queue_mb "
                      "%.0f): %s",
                      bound, waiting_.count(), waiting_.bytes() / 1048576.0, config_.max_queue,
                      config_.max_queue_mb,
                      config_.skip_while_busy ? "the oldest scans are dropped until it has room"
                                              : "the scans wait for room (the sensor is held)");
        ctx_.log().warn(text);
    }

    // The scans waiting, in queue order, with their bytes (waiting_scans.hpp): in on the
    // component's thread, out of the front when the worker takes a scan or the queue drops its
    // oldest, out of the back when the queue refused the new one (stopping).
    void count_in(const Scan& scan) {
        std::lock_guard<std::mutex> lock(queue_mutex_);
        waiting_.add(scan.memory_bytes(), scan.unpacked_bytes());
    }
    void count_out(bool front) {
        {
            std::lock_guard<std::mutex> lock(queue_mutex_);
            if (front) {
                waiting_.remove_front();
            } else {
                waiting_.remove_back();
            }
        }
        room_cv_.notify_all();
    }

    // --- the worker thread: the long-term map, the passes and their outputs ---

    // One scan into the long-term map, and a pass when one is due. A stop that abandons the
    // queue (not the default: it finishes) leaves the pass to the end of the session.
    void work(Scan& scan, const StopToken& stop) {
        stamp_ = scan.stamp;
        count_out(true);
        try {
            if (scan.packed) {
                scan.points = unpack_points(*scan.packed);
                scan.packed.reset();
            }
            if (!started_) {
                map_->begin_session(session_, stamp_);
                started_ = true;
                last_pass_ = stamp_;
            }
            // Paced between the regions a scan's view pages in and judges, too (a kidnap's first
            // view: a dozen regions).
            map_->add_scan(scan.points, scan.T_world_sensor, stamp_, [&] { pace(stop); });
            ++used_;
            pace(stop);
            if (config_.maintain_every_s > 0 && stamp_ - last_pass_ >= config_.maintain_every_s &&
                !stop.stop_requested()) {
                last_pass_ = stamp_;
                finish_pass(map_->maintain([&] { pace(stop); }), stamp_);
            }
        } catch (const std::exception& e) {
            event(StatusLevel::kError, StatusCode::kMaintenanceFailed, common::one_line(e.what()),
                  stamp_);
        }
    }

    // cpu_share: waits until the worker's CPU time is back within its share (see the file
    // comment); at once when stopping.
    void pace(const StopToken& stop) {
        if (!pacer_) return;
        double wait = pacer_->wait_after(common::thread_cpu_s(), common::steady_wall_s());
        while (wait > 0.0 && !stopping_ && !stop.stop_requested()) {
            const double slice = std::min(wait, kPaceSlice);
            std::this_thread::sleep_for(std::chrono::duration<double>(slice));
            wait -= slice;
            paced_wait_s_ += slice;
        }
        pacer_->waited(common::steady_wall_s());
    }

    // The session's last pass and the map saved (after the worker stopped).
    // In a site's session without a scan, the map as loaded goes to the staging all the same:
    // the site's next version keeps what earlier sessions learnt.
    void end_session() {
        const bool carry = !started_ && !config_.site_dir.empty();
        if (!started_ && !carry) return;
        const double stamp = stamp_;
        try {
            if (started_) finish_pass(map_->end_session(), stamp);
            if (!records_.empty()) {
                const fs::path ply = fs::path(config_.output_dir) / "changes_removed_added.ply";
                try {
                    write_change_ply(ply.string(), records_);
                } catch (const std::exception& e) {
                    event(StatusLevel::kError, StatusCode::kWriteFailed, common::one_line(e.what()),
                          stamp);
                }
            }
            if (!save_file_.empty()) {
                const fs::path parent = fs::path(save_file_).parent_path();
                if (!parent.empty()) fs::create_directories(parent);  // throws: one line below
                map_->save(save_file_);
                const LongTermMapStats st = map_->stats();
                const std::string what = std::to_string(st.voxels) + " voxels, session " +
                                         std::to_string(session_) + " of " +
                                         std::to_string(map_->sessions().size());
                std::string paging;
                if (config_.paging_radius > 0.0) {
                    paging = "; paging: " + std::to_string(st.regions_paged) + " of " +
                             std::to_string(st.regions) + " regions on disk, " +
                             std::to_string(st.pages_out) + " written out and " +
                             std::to_string(st.pages_in) + " read back in the session";
                }
                ctx_.log().info("map saved to " + save_file_ + ": " + what + paging);
                ctx_.report_output("maintained map", save_file_, true, what);
            }
        } catch (const std::exception& e) {
            event(StatusLevel::kError, StatusCode::kMaintenanceFailed, common::one_line(e.what()),
                  stamp);
            if (!save_file_.empty())
                ctx_.report_output("maintained map", save_file_, false, common::one_line(e.what()));
        }
    }

    void finish_pass(const ChangeSet& c, double stamp) {
        const std::uint32_t pass = passes_++;
        const LongTermMapStats st = map_->stats();
        char text[300];
        std::snprintf(text, sizeof text,
                      "pass %u: %zu moving, %zu vanished, %zu new segments; %zu voxels removed; "
                      "map %zu voxels, %.1f MiB (%zu voxels paged out); %.0f ms",
                      pass, c.count(ChangeReason::kMoving), c.count(ChangeReason::kVanished),
                      c.count(ChangeReason::kNew), c.voxels_removed, st.voxels,
                      st.memory_bytes / 1048576.0, st.voxels_paged, c.time_ms);
        event(StatusLevel::kOk, StatusCode::kMaintained, text, stamp);
        ctx_.report_memory("map", st.memory_bytes - st.views_bytes - st.motion_bytes);
        ctx_.report_memory("views", st.views_bytes);
        ctx_.report_memory("motion", st.motion_bytes);
        if (!c.changes.empty()) changes_out_.publish(*to_msg(c, pass, stamp, frame_id()));
        if (config_.output_dir.empty()) return;
        const fs::path dir(config_.output_dir);
        char name[40];
        std::snprintf(name, sizeof name, "changes_%04u.ltmc", pass);
        try {
            write_change_record((dir / name).string(), c);
            records_.push_back((dir / name).string());
            write_change_summary(summary_, c, pass);
            summary_.flush();
        } catch (const std::exception& e) {
            event(StatusLevel::kError, StatusCode::kWriteFailed, common::one_line(e.what()), stamp);
        }
    }

    std::string frame_id() {
        std::lock_guard<std::mutex> lock(mutex_);
        return frame_id_;
    }

    // ", N left out (a scan every D m)" with view_distance, else "".
    std::string spacing_note() const {
        if (config_.views.distance <= 0.0) return "";
        char text[120];
        std::snprintf(text, sizeof text, ", %llu left out (a scan every %g m)",
                      static_cast<unsigned long long>(views_.left_out()), config_.views.distance);
        return text;
    }

    // Thread-safe: the publisher and the logger are.
    void event(StatusLevel level, StatusCode code, const std::string& text, double stamp) {
        convert::log_status(ctx_.log(), level, text);
        events_out_.publish(*convert::to_msg(convert::StatusData{
            convert::to_time(stamp), frame_id(), ctx_.name(), level, code, text}));
    }

    runtime::ComponentContext& ctx_;
    MaintenanceComponentConfig config_;

    // The component's thread.
    runtime::StampPairer<Points, Eigen::Isometry3d> pairer_;
    ViewSpacing views_{config_.views};  // which scans are taken (view_distance)
    std::uint64_t scans_ = 0, no_pose_ = 0, packed_ = 0;

    // The waiting scans, their bytes and peaks (queue_mutex_).
    std::mutex queue_mutex_;
    WaitingScans waiting_;
    std::uint64_t dropped_for_bytes_ = 0;
    double waited_for_room_s_ = 0.0;  // the component's thread (offline)
    std::condition_variable room_cv_;

    // Shared with the worker (under mutex_).
    std::mutex mutex_;
    std::string frame_id_ = "map";

    // The worker's (read by on_shutdown after the join).
    std::string load_file_, save_file_;                 // the maintained map's ("": none)
    std::shared_ptr<map::StagingClaim> staging_claim_;  // with site_dir: the session's staging
    std::unique_ptr<LongTermMap> map_;
    std::uint32_t session_ = 0;
    bool started_ = false;
    double last_pass_ = 0.0, stamp_ = 0.0;
    std::uint64_t used_ = 0;
    std::uint32_t passes_ = 0;
    std::optional<common::CpuPacer> pacer_;  // cpu_share < 1, or cpu_budget
    double paced_wait_s_ = 0.0;
    std::atomic<bool> stopping_{false};
    std::vector<std::string> records_;  // the passes' change records written (the PLY's)
    std::ofstream summary_;

    runtime::Publisher<msg::MapChangeSet> changes_out_;
    runtime::Publisher<msg::Status> events_out_;
    Worker worker_;  // last: stopped before the members it uses go
};

}  // namespace
}  // namespace ltm::maintenance

LTM_REGISTER_COMPONENT(
    ltm::maintenance::MaintenanceComponent, "maintenance",
    "map maintenance: registered scans and their poses in; map_changes and change reports out")
