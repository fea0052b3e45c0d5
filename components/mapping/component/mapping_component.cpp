// The SLAM back end as a component: `local_map`, `keyframe` and `odometry` in (from the odometry);
// loop closures, the optimised `pose_graph`, the corrected keyframe trajectory (`path`), the
// corrected full-rate odometry (`corrected_odometry`, frame `map`) and the `map_to_odom`
// correction out. The optimisation runs on this component's own thread, off the odometry's.
// The map is saved (`map_dir`) as it goes, on request (`map_request`) and at shutdown; the global
// voxel map is written as PLY (`global_map_file`) on request and at shutdown (requests to write
// the mesh are the mesh component's: left alone). With `load_map_dir` a saved map is continued in
// a new session. `status` says when the odometry restarted in a new segment (until a loop joins
// it, its corrected poses are the odometry's best estimate across the break) and when a loop joins
// that segment to the map.
// Several robots at once (`robots: [robot1, robot2]`): a mapper session a robot; for each robot R
// the inputs are /R/keyframe, /R/local_map, /R/odometry and the outputs /R/map_to_odom,
// /R/corrected_odometry and /R/path, while pose_graph, loop_closure and status are shared; `status`
// also says when a robot's session is joined to the map by a loop (until then its poses are its own
// odometry's); each robot's /R/map_changes (its maintenance's, over its uplink) edit the local
// maps. Without robots (the default) the topic names are relative, as for one robot.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <deque>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <set>

#include "common/core/cpu_budget.hpp"
#include "common/core/cpu_pacer.hpp"
#include "common/core/io_error.hpp"
#include "common/core/ply_io.hpp"
#include "common/core/sensor_detect.hpp"
#include "common/core/thread_clock.hpp"
#include "map/core/link_applied.hpp"
#include "map/core/map_store.hpp"
#include "map/core/site_staging.hpp"
#include "map/core/site_store.hpp"
#include "mapping/component/map_edit_inputs.hpp"
#include "mapping/component/map_saver.hpp"
#include "mapping/component/mapper_messages.hpp"
#include "mapping/component/place_descriptor_msg.hpp"
#include "mapping/core/mapper.hpp"
#include "mapping/params/mapper_params.hpp"
#include "runtime/component.hpp"
#include "runtime/convert/dds_string.hpp"
#include "runtime/convert/geometry.hpp"
#include "runtime/convert/local_map.hpp"
#include "runtime/convert/odometry.hpp"
#include "runtime/convert/path.hpp"
#include "runtime/convert/status.hpp"
#include "runtime/convert/transform.hpp"
#include "runtime/link_messages.hpp"

namespace ltm::mapping {
namespace {

using common::StatusCode;
using convert::StatusLevel;
using runtime::PathCheck;
using runtime::TopicRole;

class MappingComponent : public runtime::Component {
  public:
    explicit MappingComponent(runtime::ComponentContext& ctx) : ctx_(ctx) {
        auto& p = ctx.params();
        map_dir_ = p.path("map_dir", "", PathCheck::kParentExists);
        global_map_file_ = p.path("global_map_file", "", PathCheck::kParentExists);
        std::string load_dir = p.path("load_map_dir", "", PathCheck::kDirExists);
        resolve_site(p, &load_dir);
        const bool freeze_loaded = p.get<bool>("freeze_loaded", true);
        frame_id_ = p.get<std::string>("frame_id", "map");
        const double save_period = p.get<double>("save_period_s", 30.0);
        if (save_period < 0)
            p.fail("save_period_s", "must be >= 0 (0: save only on request and at shutdown)");
        const std::vector<std::string> robots = p.get<std::vector<std::string>>("robots", {});
        // Ties to a loaded map by the localisation on it (one robot), and what maintenance found.
        MapEditInputs::Options edits;
        edits.subscribe_fixes = p.get<bool>("localisation_fixes", true) && robots.empty();
        edits.use_fixes = edits.subscribe_fixes && !load_dir.empty();
        edits.fix_after = p.get<int>("localisation_fix_after", 3);
        if (edits.fix_after < 1)
            p.fail("localisation_fix_after", "must be >= 1 (scans tracked in a row)");
        edits.apply_changes = p.get<bool>("apply_map_changes", true);
        edits.clear_share = p.get<double>("map_changes_cpu_share", edits.clear_share);
        if (!(edits.clear_share > 0.0 && edits.clear_share <= 1.0))
            p.fail("map_changes_cpu_share", "must be in (0, 1] (1: a pass's edits all at once)");
        // A CPU budget shared with the process's other background work (the maintenance's
        // `cpu_budget`, the same name; common/core/cpu_budget.hpp): the clearing draws from it and
        // the periodic saves (on their own thread, map_saver.hpp) draw from it file by file.
        if (const std::string name = p.get<std::string>("cpu_budget", ""); !name.empty()) {
            std::string error;
            edits.budget = common::shared_cpu_budget(name, edits.clear_share, kBudgetBurst, &error);
            if (!edits.budget) p.fail("cpu_budget", error);
        }
        edits.frame_id = frame_id_;
        const bool edits_budget = edits.budget != nullptr;
        const MapperConfig config = load_mapper_config(p, "", common::kAutoPreset);
        if (p.get<std::string>("preset", common::kAutoPreset) == common::kAutoPreset)
            ctx.log().info(
                "preset auto: the spinning sensors' settings (hdl64, vlp32, vlp16 and os1-64 share "
                "them); a narrow (Livox type) sensor needs preset: narrow");
        // The robots' link packets this map holds (map/core/link_applied.hpp): the loaded map's,
        // then what the downlinks hand on and this component takes; written beside every save.
        delivery_ = map::DeliveryTracker(edits.apply_changes);
        create_mapper(p, config, load_dir, freeze_loaded);
        check_robots(p, robots);
        if (!map_dir_.empty()) {
            map::SaveOptions options;
            options.link_from = link_from_;  // unchanged files of the start version: hard links
            saver_ = std::make_unique<MapSaver>(
                ctx.name(), map_dir_, options, edits.budget,
                [this](bool ok, const std::string& line) { report(ok, line, nullptr); });
        }
        // Saving as it goes keeps the save at shutdown small (only what changed is rewritten),
        // and a crash loses at most one period.
        // On a site, the local maps far from the robots leave memory once a save holds them
        // unchanged, and are read back from the session's map directory when needed (mapper.hpp,
        // PagingConfig); a plain map_dir run keeps them all.
        if (saver_ && !site_dir_.empty()) {
            mapper_->set_local_map_loader([dir = map_dir_](const map::LocalMapFile& f) {
                return map::load_local_map(dir, f).data;
            });
        }
        if (saver_ && save_period > 0) ctx.add_timer(save_period, [this] { save(); });
        // What the mapper holds, by part, for the host's minute memory line.
        ctx.add_timer(runtime::kMemoryReportPeriod, [this] {
            const Mapper::Memory m = mapper_->memory();
            ctx_.report_memory("local maps", m.local_maps);
            ctx_.report_memory("keyframes", m.keyframes);
            ctx_.report_memory("graph", m.graph);
            ctx_.report_memory("loop targets", m.loop_targets);
            ctx_.report_memory("removed cells", m.removed_cells);
        });
        // One robot (relative topic names, the mapper's default session), or one a robot.
        for (const std::string& name : robots.empty() ? std::vector<std::string>{""} : robots) {
            auto robot = std::make_unique<Robot>();
            robot->name = name;
            robot->session = name.empty() ? mapper_->session() : mapper_->open_session(name);
            Robot* r = robot.get();
            ctx.subscribe<msg::LocalMap>(
                topic(*r, "local_map"), TopicRole::kMap,
                [this, r](const msg::LocalMap& m) { on_local_map(*r, m); });
            ctx.subscribe<msg::Keyframe>(topic(*r, "keyframe"), TopicRole::kState,
                                         [this, r](const msg::Keyframe& m) { on_keyframe(*r, m); });
            ctx.subscribe<msg::Odometry>(topic(*r, "odometry"), TopicRole::kState,
                                         [this, r](const msg::Odometry& m) { on_odometry(*r, m); });
            ctx.subscribe<msg::LinkDelivered>(
                topic(*r, "link/delivered"), TopicRole::kState,
                [this, r](const msg::LinkDelivered& m) {
                    delivery_.mark(r->name, convert::to_string(m.robot), m.run, m.through,
                                   {m.keyframes, m.local_maps, m.map_changes});
                });
            r->path_out = ctx.advertise<msg::Path>(topic(*r, "path"), TopicRole::kMap);
            r->odometry_out =
                ctx.advertise<msg::Odometry>(topic(*r, "corrected_odometry"), TopicRole::kState);
            r->correction_out =
                ctx.advertise<msg::TransformStamped>(topic(*r, "map_to_odom"), TopicRole::kState);
            // The version this map frame belongs to, beside map_to_odom (held for late joiners):
            // a split robot uses this map_to_odom only on that version (none: a new site).
            auto version_out =
                ctx.advertise<msg::MapVersion>(topic(*r, "map_version"), TopicRole::kMap);
            msg::MapVersion v{};
            v.site = const_cast<char*>(site_dir_.c_str());
            v.version = const_cast<char*>(start_version_.c_str());
            version_out.publish(v);
            r->version_out = std::move(version_out);
            robots_.push_back(std::move(robot));
        }
        // Each robot's maintenance findings (its uplink's map_changes), or the relative topic.
        if (!robots.empty()) {
            edits.change_topics.clear();
            for (const auto& r : robots_) edits.change_topics.push_back(topic(*r, "map_changes"));
        }
        edits_ = std::make_unique<MapEditInputs>(
            ctx, *mapper_, robots_.front()->session, edits,
            [this](const std::string& what) {
                ctx_.log().info(what);
                status(StatusLevel::kOk, StatusCode::kSessionJoined, what);
            },
            [this] { optimise(); });
        edits_->on_taken([this](std::size_t i) {
            if (i < robots_.size()) delivery_.took_map_changes(robots_[i]->name);
        });
        ctx.subscribe<msg::MapRequest>("map_request", TopicRole::kState,
                                       [this](const msg::MapRequest& m) { on_request(m); });
        graph_out_ = ctx.advertise<msg::PoseGraph>("pose_graph", TopicRole::kMap);
        loop_out_ = ctx.advertise<msg::LoopClosure>("loop_closure", TopicRole::kState);
        status_out_ = ctx.advertise<msg::Status>("status", TopicRole::kState);
        // cpu_budget: the first periodic save (its timer fires as the host starts) now, while the
        // host is configured, alone on the machine's clock like the components' loads, rather
        // than in the mission's first second beside the first scans.
        if (saver_ && save_period > 0 && edits_budget) save(map_dir_, nullptr);
    }

    void on_activate() override {
        if (saver_) saver_->start();
    }

    void on_shutdown() override {
        if (saver_) saver_->stop();  // the periodic save under way, unpaced; the last one below
        edits_->finish_clearing();   // every edit taken is in the saved map
        if (loops_since_optimise_ > 0) optimise();
        for (const auto& r : robots_) {
            publish_path(*r);
            if (!r->name.empty()) ctx_.log().info(mapper_->session_status(r->session).message);
        }
        ctx_.log().info(std::to_string(mapper_->keyframes().size()) + " keyframes, " +
                        std::to_string(mapper_->local_map_count()) + " local maps, " +
                        std::to_string(mapper_->loops().size()) + " loops closed" +
                        (mapper_->forgotten_voxels() > 0
                             ? ", " + std::to_string(mapper_->forgotten_voxels()) +
                                   " voxels forgotten (unseen by their local map's last " +
                                   std::to_string(mapper_->config().long_term.forget_after_visits) +
                                   " visits)"
                             : std::string()));
        if (const std::string edits = edits_->summary(); !edits.empty()) ctx_.log().info(edits);
        if (const Mapper::FoldStats& f = mapper_->fold_stats(); f.tried > 0) {
            std::vector<double> c = f.corrections;
            std::string median = "-";
            if (!c.empty()) {
                std::nth_element(c.begin(), c.begin() + long(c.size() / 2), c.end());
                char text[32];
                std::snprintf(text, sizeof text, "%.1f cm", 100.0 * c[c.size() / 2]);
                median = text;
            }
            ctx_.log().info("folds: " + std::to_string(f.registered) + " of " +
                            std::to_string(f.tried) +
                            " registered to the map they went into (median correction to the "
                            "graph's estimate " +
                            median + "), the others placed by the graph");
        }
        if (saver_ && !site_dir_.empty()) {
            for (const std::string& line : mapper_->take_paging_problems()) ctx_.log().warn(line);
            ctx_.log().info(
                "paging: " + std::to_string(mapper_->paged_out()) + " of " +
                std::to_string(mapper_->local_map_count()) + " local maps on disk at the end, " +
                std::to_string(mapper_->paged_in()) + " loaded back; the mapper holds " +
                mib(mapper_->memory_bytes()) + " MiB");
        }
        if (saver_ && saver_->background_saves() > 0) {
            char line[200];
            std::snprintf(line, sizeof line,
                          "periodic saves: %llu on mapping/save, %.0f ms of CPU, the longest piece "
                          "between two budget checks %.0f ms",
                          static_cast<unsigned long long>(saver_->background_saves()),
                          saver_->background_cpu_s() * 1e3, saver_->longest_piece_s() * 1e3);
            ctx_.log().info(line);
        }
        // The host lists the outputs: what a saved one holds (the parenthesis of the log line),
        // why one was not saved.
        auto detail = [](const std::string& line) {
            const auto open = line.find(" (");
            return open == std::string::npos || line.back() != ')'
                       ? line
                       : line.substr(open + 2, line.size() - open - 3);
        };
        std::string map_line, global_line;
        if (!map_dir_.empty()) {
            const bool ok = save(map_dir_, &map_line);
            ctx_.report_output("map", map_dir_, ok, detail(map_line));
        }
        if (!global_map_file_.empty()) {
            const bool ok = write_global_map(global_map_file_, &global_line);
            ctx_.report_output("global voxel map", global_map_file_, ok, ok ? "" : global_line);
        }
    }

  private:
    // With `site_dir` (map/core/site_store.hpp): the map continued is the site's start version's
    // (`site_version`, or the newest intact one; none on a new site) and it is saved into the
    // site's staging, which the `site` component makes the next version at the end.
    void resolve_site(runtime::Parameters& p, std::string* load_dir) {
        const std::string site = p.path("site_dir", "", PathCheck::kNone);
        const std::string version = p.get<std::string>("site_version", "");
        if (site.empty()) {
            if (!version.empty()) p.fail("site_version", "needs site_dir");
            return;
        }
        if (!load_dir->empty()) p.fail("load_map_dir", "give either load_map_dir or site_dir");
        if (!map_dir_.empty()) p.fail("map_dir", "give either map_dir or site_dir");
        // The staging is this session's before the first save (map/core/site_staging.hpp): the
        // site's lock, and an earlier session's staging removed; the site component, constructed
        // after this one, shares the claim and keeps what this component saved.
        bool made = false;
        try {
            staging_claim_ = map::claim_staging(site, &made);
        } catch (const common::IoError& e) {
            p.fail("site_dir", e.what());
        }
        if (made && !staging_claim_->removed().empty()) ctx_.log().warn(staging_claim_->removed());
        map::SiteSession session;
        try {
            session = map::resolve_site(site, version);
        } catch (const common::IoError& e) {
            p.fail(version.empty() ? "site_dir" : "site_version", e.what());
        }
        for (const std::string& note : session.notes) ctx_.log().warn(note);
        map_dir_ = session.staging_map_dir;  // created by the first save
        site_dir_ = site;
        if (session.start) {
            *load_dir = session.start->map_dir();
            link_from_ = *load_dir;
            start_version_ = session.start->name;
        }
        ctx_.log().info("site " + site + ": continuing " + session.describe() +
                        "; the session's map goes to " + map_dir_);
    }

    // A robot's inputs, outputs and the state of its corrected odometry.
    struct Robot {
        std::string name;  // "" without `robots`: relative topic names
        std::uint32_t session = 0;
        std::deque<convert::OdometryData> waiting;
        bool warned_waiting = false;
        bool told_loop = false, told_localisation = false;  // about its keyframes' descriptors
        std::uint64_t current_map = 0;
        bool has_current_map = false;
        std::map<std::uint32_t, bool> segment_joined;  // as last reported
        std::optional<bool> session_joined;            // as last reported
        runtime::Publisher<msg::Path> path_out;
        runtime::Publisher<msg::Odometry> odometry_out;
        runtime::Publisher<msg::TransformStamped> correction_out;
        runtime::Publisher<msg::MapVersion> version_out;
    };

    // "keyframe", or "/robot1/keyframe" for robot robot1.
    static std::string topic(const Robot& r, const std::string& name) {
        return r.name.empty() ? name : "/" + r.name + "/" + name;
    }

    // Robot names are topic namespaces: a letter, then letters, digits or '_'; each once.
    static void check_robots(runtime::Parameters& p, const std::vector<std::string>& robots) {
        std::set<std::string> seen;
        for (const std::string& r : robots) {
            const bool ok = !r.empty() && std::isalpha(static_cast<unsigned char>(r[0])) &&
                            std::all_of(r.begin(), r.end(), [](char c) {
                                return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
                            });
            if (!ok)
                p.fail("robots", "'" + r +
                                     "' is not a robot name (a letter, then letters, digits or "
                                     "'_': its topics are /NAME/...)");
            if (!seen.insert(r).second) p.fail("robots", "'" + r + "' is named twice");
        }
    }

    // "robot2: " before a robot's messages when several map at once.
    static std::string prefix(const Robot& r) { return r.name.empty() ? "" : r.name + ": "; }

    void on_local_map(Robot& r, const msg::LocalMap& m) {
        delivery_.took_local_map(r.name);  // a save runs on this thread: after this handler
        const LocalMapResult result = mapper_->add_local_map(convert::from_msg(m), r.session);
        if (!result.added && !result.message.empty()) ctx_.log().debug(prefix(r) + result.message);
        report_segments();
        flush_waiting(r);
    }

    void create_mapper(runtime::Parameters& p, const MapperConfig& config,
                       const std::string& load_dir, bool freeze_loaded) {
        try {
            if (load_dir.empty()) {
                mapper_ = std::make_unique<Mapper>(config);
                return;
            }
            map::LoadedMap loaded = map::load_map(load_dir);
            // A damaged file is left alone: saving into the same directory would replace it.
            std::error_code ec;
            if (!loaded.refused.empty() && !map_dir_.empty() &&
                std::filesystem::equivalent(load_dir, map_dir_, ec))
                p.fail("load_map_dir",
                       std::to_string(loaded.refused.size()) + " damaged file(s) in the map (" +
                           loaded.refused.front() +
                           "); set map_dir to another directory to continue without them");
            for (const std::string& r : loaded.refused)
                ctx_.log().warn("loaded map: " + r + " (left out)");
            mapper_ = std::make_unique<Mapper>(config, loaded.map, freeze_loaded);
            std::string note;
            delivery_.seed(map::read_link_applied(load_dir, &note));
            if (!note.empty()) ctx_.log().warn(note);
            ctx_.log().info("continuing the map of " + load_dir + " (" +
                            std::to_string(mapper_->local_map_count()) + " local maps, " +
                            std::to_string(mapper_->keyframes().size()) +
                            " keyframes) in session " + std::to_string(mapper_->session()));
        } catch (const map::MapFormatError& e) {
            p.fail("load_map_dir", e.what());
        } catch (const common::IoError& e) {
            p.fail("load_map_dir", e.what());
        } catch (const common::ConfigError& e) {
            // The configuration does not fit the loaded map: the key is under the mapper's section.
            p.fail(e.key().substr(e.key().find('.') + 1), e.problem());
        }
    }

    std::uint64_t state() const {
        return mapper_->revision() + mapper_->keyframes().size() + mapper_->local_map_count();
    }

    // The periodic save: only when something changed (or the last one failed), on the saver's
    // thread (map_saver.hpp), within the CPU budget when there is one. Every edit taken is in it.
    void save() {
        if (saver_) page();
        if (!saver_ || (state() == saved_state_ && !saver_->take_failed())) return;
        edits_->finish_clearing();  // a saved map never lacks an edit it acknowledged
        saved_state_ = state();
        saver_->save_in_background(mapper_->snapshot(), delivery_.applied());
    }

    static std::string mib(std::size_t bytes) {
        char text[32];
        std::snprintf(text, sizeof text, "%.1f", double(bytes) / 1048576.0);
        return text;
    }

    // Pages out the local maps far from the robots that the last save holds unchanged, and logs
    // the loads back that failed since.
    void page() {
        const std::size_t went = mapper_->page_out(saver_->written_local_maps());
        if (went > 0)
            ctx_.log().info("paged out " + std::to_string(went) + " local maps (" +
                            std::to_string(mapper_->paged_out()) + " of " +
                            std::to_string(mapper_->local_map_count()) + " on disk, " +
                            std::to_string(mapper_->paged_in()) + " loaded back so far; " +
                            mib(mapper_->memory_bytes()) + " MiB held)");
        for (const std::string& line : mapper_->take_paging_problems()) ctx_.log().warn(line);
    }

    // Saves the map to `dir`; logs the outcome and appends it to `outcome` (one line a step).
    bool save(const std::string& dir, std::string* outcome) {
        if (dir.empty()) return true;
        edits_->finish_clearing();  // a saved map never lacks an edit it acknowledged
        try {
            map::SaveStats st;
            if (saver_ && dir == map_dir_) {
                st = saver_->save_now(mapper_->snapshot(), delivery_.applied());
                saved_state_ = state();
            } else {
                st = map::save_map(dir, mapper_->complete_snapshot());
                // After the manifest: a version committed from this save holds both (the site
                // component commits only once a save is done), so its record is never ahead.
                if (!delivery_.applied().empty()) map::save_link_applied(dir, delivery_.applied());
            }
            return report(true, MapSaver::describe(dir, st), outcome);
        } catch (const common::IoError& e) {
            return report(false, std::string("map not saved: ") + e.what(), outcome);
        }
    }

    bool write_global_map(const std::string& file, std::string* outcome) {
        if (file.empty()) return true;
        edits_->finish_clearing();
        try {
            common::write_ply(file, mapper_->global_map());
            return report(true, "global voxel map written to " + file, outcome);
        } catch (const common::IoError& e) {
            return report(false, std::string("global voxel map not written: ") + e.what(), outcome);
        }
    }

    bool report(bool ok, const std::string& line, std::string* outcome) const {
        if (ok) {
            ctx_.log().info(line);
        } else {
            ctx_.log().error(line);
        }
        if (outcome) *outcome += (outcome->empty() ? "" : "; ") + line;
        return ok;
    }

    void on_request(const msg::MapRequest& m) {
        if (m.command == ltm_msgs_msg_MapRequest_Constants_WRITE_MESH ||
            m.command == ltm_msgs_msg_MapRequest_Constants_COMMIT_VERSION)
            return;  // the mesh's, the site's
        const std::string requested_dir = convert::to_string(m.map_dir);
        const std::string requested_file = convert::to_string(m.global_map_file);
        const std::string dir = requested_dir.empty() ? map_dir_ : requested_dir;
        const std::string file = requested_file.empty() ? global_map_file_ : requested_file;
        const bool want_map = m.command == ltm_msgs_msg_MapRequest_Constants_SAVE_MAP ||
                              m.command == ltm_msgs_msg_MapRequest_Constants_SAVE_ALL;
        const bool want_ply = m.command == ltm_msgs_msg_MapRequest_Constants_WRITE_GLOBAL_MAP ||
                              m.command == ltm_msgs_msg_MapRequest_Constants_SAVE_ALL;
        std::string outcome;
        bool ok = false;
        if (!want_map && !want_ply) {
            outcome = "unknown command " + std::to_string(m.command);
        } else if ((want_map && dir.empty()) || (want_ply && file.empty())) {
            outcome = std::string("nowhere to write: no ") +
                      (want_map && dir.empty() ? "map_dir" : "global_map_file") +
                      " in the request or the component's parameters";
        } else {
            if (loops_since_optimise_ > 0) optimise();
            const bool map_ok = !want_map || save(dir, &outcome);
            const bool ply_ok = !want_ply || write_global_map(file, &outcome);
            ok = map_ok && ply_ok;
        }
        status(ok ? StatusLevel::kOk : StatusLevel::kError,
               ok ? StatusCode::kMapRequestDone : StatusCode::kMapRequestFailed,
               "request " + std::to_string(m.id) + ": " + outcome, m.id);
    }

    void on_keyframe(Robot& robot, const msg::Keyframe& m) {
        delivery_.took_keyframe(robot.name);  // a save runs on this thread: after this handler
        KeyframeDescriptors given;
        given.loop = descriptor(robot, m.descriptor, mapper_->config().scan_context, "scan_context",
                                &robot.told_loop);
        given.localisation =
            descriptor(robot, m.localisation_descriptor, mapper_->config().localisation_descriptor,
                       "localisation_descriptor", &robot.told_localisation);
        const common::KeyframeData keyframe = convert::from_msg(m);
        const KeyframeResult r = mapper_->add_keyframe(keyframe, robot.session, given);
        if (!r.added) {
            ctx_.log().warn(prefix(robot) + "keyframe " + std::to_string(m.id) +
                            " not added: " + r.message);
            return;
        }
        robot.current_map = m.local_map_id;
        robot.has_current_map = true;
        flush_waiting(robot);
        for (const LoopClosure& loop : r.loops) publish_loop(loop, m.header.stamp);
        for (const LoopRejection& j : r.rejected) {  // map_edge: worth knowing, once a keyframe
            if (j.reason.rfind("at the loaded map's edge", 0) != 0) continue;
            ctx_.log().info(prefix(robot) + "loop not tied: scan " +
                            std::to_string(keyframe.scan_index) + " " + j.reason);
            break;
        }
        loops_since_optimise_ += r.loops.size();
        if (r.optimisation_due()) optimise();
        edits_->keyframe(keyframe, r.index);
        publish_correction(robot, m.header.stamp);
    }

    // A keyframe's descriptor made on the robot (keyframe_digest); made here again from its points
    // (said once a robot) when it is damaged or made with other settings than the mapping's.
    MadeDescriptor descriptor(const Robot& robot, const msg::PlaceDescriptor& m,
                              const places::ScanContextConfig& mine, const std::string& key,
                              bool* told) {
        std::string problem;
        MadeDescriptor d = from_msg(m, &problem);
        if (problem.empty() && !d.descriptor.empty() && !usable(d, mine))
            problem = "made with other settings than mapping." + key +
                      " (set the robot's keyframe_digest as the mapping)";
        if (!problem.empty() && !*told) {
            *told = true;
            ctx_.log().warn(prefix(robot) + "keyframe " + key + " descriptors: " + problem +
                            "; made here from the keyframe's points instead");
        }
        return d;
    }

    // The odometry pose corrected by the newest keyframe's local map: T_world_odom * T_odom_lidar.
    // Poses wait until that correction is known (the odometry publishes a frame's pose before its
    // keyframe, and a new local map some time after its first keyframe).
    void on_odometry(Robot& r, const msg::Odometry& m) {
        if (r.waiting.empty()) {
            if (const std::optional<Eigen::Isometry3d> T = correction(r)) {
                publish_corrected(r, convert::from_msg(m), *T);
                return;
            }
        }
        if (r.waiting.size() == kMaxWaiting) {
            r.waiting.pop_front();
            if (!r.warned_waiting)
                ctx_.log().warn(prefix(r) +
                                "no local map for the odometry's poses yet: the oldest waiting "
                                "ones are dropped");
            r.warned_waiting = true;
        }
        r.waiting.push_back(convert::from_msg(m));
        flush_waiting(r);
    }

    std::optional<Eigen::Isometry3d> correction(const Robot& r) const {
        return r.has_current_map ? mapper_->T_world_odom(r.current_map, r.session) : std::nullopt;
    }

    void flush_waiting(Robot& r) {
        if (r.waiting.empty()) return;
        const std::optional<Eigen::Isometry3d> T = correction(r);
        if (!T) return;
        for (const convert::OdometryData& o : r.waiting) publish_corrected(r, o, *T);
        r.waiting.clear();
    }

    void publish_corrected(Robot& r, const convert::OdometryData& o,
                           const Eigen::Isometry3d& T_world_odom) {
        r.odometry_out.publish(*convert::to_msg(convert::reparent(o, T_world_odom, frame_id_)));
    }

    void publish_correction(Robot& r, const msg::Time& stamp) {
        const std::optional<Eigen::Isometry3d> T = correction(r);
        if (!T) return;
        r.correction_out.publish(
            *convert::to_msg(convert::TransformData{stamp, frame_id_, "odom", *T}));
    }

    void optimise() {
        const OptimisationSummary s = mapper_->optimise();
        loops_since_optimise_ = 0;
        if (!s.solved) {
            ctx_.log().warn("pose graph not solved: " + s.message);
            status(StatusLevel::kWarn, StatusCode::kNotSolved, s.message);
            return;
        }
        publish_graph();
        for (const auto& r : robots_) publish_path(*r);
        report_segments();
    }

    // A new odometry segment (the odometry lost track and restarted), and its joining by a loop:
    // one status each time a segment's state changes; with several robots, each robot's session
    // joined to the map or not, the same way.
    void report_segments() {
        for (const auto& robot : robots_) {
            Robot& r = *robot;
            for (const SegmentStatus& s : mapper_->segments(r.session)) {
                if (s.segment == 0) continue;
                const auto it = r.segment_joined.find(s.segment);
                if (it != r.segment_joined.end() && it->second == s.joined) continue;
                r.segment_joined[s.segment] = s.joined;
                report_joined(s.joined ? StatusCode::kSegmentJoined : StatusCode::kSegmentNotJoined,
                              prefix(r) + s.message);
            }
            if (r.name.empty()) continue;
            const SessionStatus st = mapper_->session_status(r.session);
            if (r.session_joined == st.joined ||
                st.message.find("has no local map") != std::string::npos)
                continue;
            r.session_joined = st.joined;
            report_joined(st.joined ? StatusCode::kSessionJoined : StatusCode::kSessionNotJoined,
                          st.message);
        }
    }

    // A segment or session joined (ok, logged as info) or not (warn).
    void report_joined(StatusCode code, const std::string& message) {
        const bool joined =
            code == StatusCode::kSegmentJoined || code == StatusCode::kSessionJoined;
        if (joined) {
            ctx_.log().info(message);
        } else {
            ctx_.log().warn(message);
        }
        status(joined ? StatusLevel::kOk : StatusLevel::kWarn, code, message);
    }

    void status(StatusLevel level, StatusCode code, const std::string& message,
                std::uint32_t request_id = 0) {
        status_out_.publish(*convert::to_msg(
            convert::StatusData{{}, frame_id_, ctx_.name(), level, code, message, 0, request_id}));
    }

    void publish_loop(const LoopClosure& loop, const msg::Time& stamp) {
        loop_out_.publish(*convert::to_msg(loop_data(*mapper_, loop, stamp, frame_id_)));
        auto who = [this](std::uint32_t session) {
            const std::string robot = mapper_->robot(session);
            return robot.empty() ? "session " + std::to_string(session) : robot;
        };
        const std::string other =
            loop.match_session == loop.query_session ? "" : " of " + who(loop.match_session);
        const std::string own = robots_.size() > 1 ? who(loop.query_session) + ": " : "";
        ctx_.log().info(own + "loop closed: scan " + std::to_string(loop.query_scan) +
                        " with scan " + std::to_string(loop.match_scan) + other + " (" +
                        std::to_string(loop.inliers) + " inliers, worst direction " +
                        std::to_string(int(std::lround(100.0 * loop.min_sector_fraction))) +
                        " % explained)");
    }

    void publish_graph() { graph_out_.publish(*convert::to_msg(graph_data(*mapper_, frame_id_))); }

    // The corrected trajectory of a robot's session: its keyframes at their optimised poses.
    void publish_path(Robot& r) {
        r.path_out.publish(*convert::to_msg(session_path(*mapper_, r.session), frame_id_));
    }

    runtime::ComponentContext& ctx_;
    std::unique_ptr<Mapper> mapper_;
    std::string map_dir_, global_map_file_, frame_id_, link_from_;
    std::size_t loops_since_optimise_ = 0;
    std::vector<std::unique_ptr<Robot>> robots_;  // callbacks hold their robot's address
    std::unique_ptr<MapSaver> saver_;             // map_dir's saves
    std::uint64_t saved_state_ = 0;
    static constexpr double kBudgetBurst = 0.1;  // [s] of CPU, when this component creates it
    std::string site_dir_, start_version_;       // site_dir; the version continued ("": none)
    std::shared_ptr<map::StagingClaim> staging_claim_;  // with site_dir: the session's staging
    map::DeliveryTracker delivery_;
    std::unique_ptr<MapEditInputs> edits_;            // holds the mapper: declared after it
    static constexpr std::size_t kMaxWaiting = 1000;  // 100 s at 10 Hz
    runtime::Publisher<msg::PoseGraph> graph_out_;
    runtime::Publisher<msg::LoopClosure> loop_out_;
    runtime::Publisher<msg::Status> status_out_;
};

}  // namespace
}  // namespace ltm::mapping

LTM_REGISTER_COMPONENT(
    ltm::mapping::MappingComponent, "mapping",
    "SLAM back end: Scan Context loops, pose graph, corrected path and odometry, map saved")
