// ltm_bench_multi_robot: several robots mapping one site at once into one Mapper. Two sessions of
// a simulator scenario (default: site_sessions' first two) are driven at the same time, scan i of
// each in turn, as robot1 and robot2: each robot has its own odometry and hand-over, the one
// Mapper a session a robot (Mapper::open_session). Prints per robot: scans, path length, ATE
// (SE(3)-aligned on its own, and with one alignment for both robots: the one map's consistency),
// as % of its path, the revisits of the other robot's places (within --radius of a place the
// other one had passed by then) and how many a loop between the robots closed (at one of their
// frames, or joining their local maps: cross_revisits.hpp), the loops, and
// whether its session is joined to the map; then the graph (nodes, edges, connected parts).
// LTM_BENCH_LOOPS=1 prints every loop and refusal. `./ltm bench multi_robot --help`.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "common/cli/cli.hpp"
#include "common/core/progress.hpp"
#include "common/core/sensor_preset.hpp"
#include "common/core/trajectory_io.hpp"
#include "evaluation/core/ate.hpp"
#include "map/core/map_store.hpp"
#include "mapping/bench/cross_revisits.hpp"
#include "mapping/bench/sim_source.hpp"
#include "mapping/core/mapper.hpp"
#include "mapping/params/mapper_params.hpp"
#include "odometry/core/map_handover.hpp"
#include "odometry/core/odometry.hpp"
#include "odometry/params/odometry_params.hpp"

namespace {

using namespace ltm;
using Clock = std::chrono::steady_clock;

struct Args {
    std::string scenario = LTM_SOURCE_DIR "/components/simulator/scenarios/site_sessions.yaml";
    std::vector<int> sessions = {0, 1};
    std::string preset = "vlp32", config, mapping_config, out;
    std::size_t max_frames = 0;
    double radius = 5.0;
    // The odometry's snapshots of its active local maps (the component's default; robot.yaml sends
    // finished maps only, 0).
    int snapshot_every = odometry::HandoverConfig{}.snapshot_every_keyframes;
};

// One robot: its scans, odometry, hand-over and what it did.
struct Robot {
    std::string name;
    std::uint32_t session = 0;
    std::unique_ptr<mapping::bench::SimSource> source;
    std::unique_ptr<odometry::Odometry> odometry;
    std::unique_ptr<odometry::MapHandover> handover;
    std::size_t frames = 0;
    common::PoseList odom, reference;
    std::vector<std::uint64_t> frame_map;
};

double path_length(const common::PoseList& poses) {
    double path = 0.0;
    for (std::size_t i = 1; i < poses.size(); ++i)
        path += (poses[i].translation() - poses[i - 1].translation()).norm();
    return path;
}

// Off the truth by more than 1 m or 5 deg.
bool false_loop(const mapping::LoopClosure& l, const Robot& query, const Robot& match) {
    if (l.query_scan >= query.frames || l.match_scan >= match.frames) return false;
    const Eigen::Isometry3d e =
        (match.reference[l.match_scan].inverse() * query.reference[l.query_scan]).inverse() *
        l.T_match_query;
    return e.translation().norm() > 1.0 || Eigen::AngleAxisd(e.linear()).angle() > 5.0 * M_PI / 180;
}

int run(const Args& a) {
    const common::SensorPreset preset = common::parse_sensor_preset(a.preset);
    const odometry::OdometryConfig oc = a.config.empty()
                                            ? odometry::preset_config(preset)
                                            : odometry::load_odometry_config_file(a.config);
    const mapping::MapperConfig mc =
        a.mapping_config.empty() ? mapping::mapper_preset(preset)
                                 : mapping::load_mapper_config_file(a.mapping_config, a.preset);
    mapping::Mapper mapper(mc);
    std::vector<std::unique_ptr<Robot>> robots;
    for (std::size_t r = 0; r < a.sessions.size(); ++r) {
        auto robot = std::make_unique<Robot>();
        robot->name = "robot" + std::to_string(r + 1);
        robot->session = mapper.open_session(robot->name);
        mapping::bench::SimSourceOptions so;
        so.scenario = a.scenario;
        so.session = a.sessions[r];
        robot->source = std::make_unique<mapping::bench::SimSource>(so);
        robot->odometry = std::make_unique<odometry::Odometry>(oc);
        odometry::HandoverConfig hc;
        hc.snapshot_every_keyframes = a.snapshot_every;
        robot->handover = std::make_unique<odometry::MapHandover>(hc);
        robot->frames =
            a.max_frames ? std::min(a.max_frames, robot->source->size()) : robot->source->size();
        robot->reference = robot->source->reference();
        robot->reference.resize(robot->frames);
        robot->odom.resize(robot->frames);
        robot->frame_map.resize(robot->frames);
        std::printf("%s (mapper session %u): %s, %zu scans\n", robot->name.c_str(), robot->session,
                    robot->source->describe().c_str(), robot->frames);
        robots.push_back(std::move(robot));
    }
    std::size_t longest = 0, total = 0, optimisations = 0, failed = 0;
    for (const auto& r : robots) {
        longest = std::max(longest, r->frames);
        total += r->frames;
    }
    const bool verbose = std::getenv("LTM_BENCH_LOOPS") != nullptr;  // every loop and refusal
    const auto t_start = Clock::now();
    auto optimise = [&] {
        ++optimisations;
        const mapping::OptimisationSummary s = mapper.optimise();
        if (!s.solved) {
            ++failed;
            std::fprintf(stderr, "optimisation failed: %s\n", s.message.c_str());
        }
    };
    common::Progress progress("multi_robot", total);
    std::size_t done = 0;
    for (std::size_t i = 0; i < longest; ++i) {
        for (const auto& r : robots) {
            if (i >= r->frames) continue;
            const odometry::FrameResult f = r->odometry->register_frame(r->source->load(i));
            r->odom[i] = f.T_odom_lidar;
            r->frame_map[i] = f.local_map_id;
            const odometry::Handover h = r->handover->after_frame(*r->odometry, f, i);
            // As the mapping component: the keyframe, an optimisation when due, then the maps.
            if (h.keyframe) {
                const mapping::KeyframeResult k = mapper.add_keyframe(*h.keyframe, r->session);
                if (!k.added) std::fprintf(stderr, "%s: %s\n", r->name.c_str(), k.message.c_str());
                if (verbose) {
                    for (const mapping::LoopRejection& j : k.rejected) {
                        const map::StoredKeyframe& m = *mapper.keyframes()[j.match_keyframe];
                        std::printf(
                            "  %s scan %zu: refused scan %lu of session %u (distance "
                            "%.3f): %s\n",
                            r->name.c_str(), i, (unsigned long)m.data.scan_index, m.session,
                            j.descriptor_distance, j.reason.c_str());
                    }
                    for (const mapping::LoopClosure& l : k.loops) {
                        std::printf("  %s scan %zu: loop with scan %lu of session %u%s\n",
                                    r->name.c_str(), i, (unsigned long)l.match_scan,
                                    l.match_session, l.across_break ? " (across a break)" : "");
                    }
                }
                if (k.optimisation_due()) optimise();
            }
            for (const common::LocalMapData& m : h.local_maps) mapper.add_local_map(m, r->session);
            progress.update(++done);
        }
    }
    for (const auto& r : robots) {
        for (const common::LocalMapData& m : r->handover->finish(*r->odometry))
            mapper.add_local_map(m, r->session);
    }
    const mapping::OptimisationSummary final_opt = mapper.optimise();
    progress.finish();
    const double seconds = std::chrono::duration<double>(Clock::now() - t_start).count();

    if (verbose) {  // the loop edges between the robots' sessions after the last optimisation
        for (const map::PoseGraphEdge& e : mapper.graph().edges()) {
            const map::PoseGraphNode* from = mapper.graph().find(e.from);
            const map::PoseGraphNode* to = mapper.graph().find(e.to);
            if (e.kind != map::EdgeKind::kLoop || from->session == to->session) continue;
            std::printf(
                "  loop edge session %u segment %u -> session %u segment %u (keyframe %lu): "
                "%s, error %.3f m\n",
                from->session, mapper.segment_of(e.from), to->session, mapper.segment_of(e.to),
                (unsigned long)e.query_keyframe, e.active ? "active" : "disabled",
                e.error_translation);
        }
    }
    // Corrected poses; the one alignment of every robot's poses together.
    common::PoseList all_est, all_ref;
    std::vector<common::PoseList> est(robots.size());
    for (std::size_t k = 0; k < robots.size(); ++k) {
        const Robot& r = *robots[k];
        for (std::size_t i = 0; i < r.frames; ++i) {
            const std::optional<Eigen::Isometry3d> w =
                mapper.T_world_lidar(r.frame_map[i], r.odom[i], r.session);
            est[k].push_back(w ? *w : r.odom[i]);
        }
        all_est.insert(all_est.end(), est[k].begin(), est[k].end());
        all_ref.insert(all_ref.end(), r.reference.begin(), r.reference.end());
    }
    const eval::AteDetail joint = eval::compute_ate_detail(all_est, all_ref);
    std::size_t false_loops = 0;
    std::printf("\n%zu scans in %.1f s, %zu optimisations (%zu failed)\n", total, seconds,
                optimisations, failed);
    for (std::size_t k = 0; k < robots.size(); ++k) {
        const Robot& r = *robots[k];
        const double path = path_length(r.reference);
        const eval::AteResult own = eval::compute_ate(est[k], r.reference);
        const eval::AteResult shared =
            eval::compute_ate(eval::transform_poses(joint.T_ref_est, est[k]), r.reference, false);
        std::size_t intra = 0, cross = 0, cross_false = 0;
        std::vector<std::size_t> frames_with_others;  // this robot's frames in loops with others
        // Per other robot: the frames of the loops with it (this robot's, the other's).
        std::vector<std::vector<std::pair<std::size_t, std::size_t>>> with(robots.size());
        for (const mapping::LoopClosure& l : mapper.loops()) {
            const bool query = l.query_session == r.session, match = l.match_session == r.session;
            if (!query && !match) continue;
            const Robot* q = nullptr;
            const Robot* m = nullptr;
            for (const auto& o : robots) {
                if (o->session == l.query_session) q = o.get();
                if (o->session == l.match_session) m = o.get();
            }
            if (query && match) {
                ++intra;
                if (q && false_loop(l, *q, *q)) ++false_loops;
                continue;
            }
            if (query) {
                ++cross;
                if (q && m && false_loop(l, *q, *m)) {
                    ++cross_false;
                    ++false_loops;
                    continue;
                }
            }
            frames_with_others.push_back(query ? l.query_scan : l.match_scan);
            for (std::size_t o = 0; o < robots.size(); ++o) {
                if (robots[o]->session == (query ? l.match_session : l.query_session))
                    with[o].push_back(query ? std::make_pair(l.query_scan, l.match_scan)
                                            : std::make_pair(l.match_scan, l.query_scan));
            }
        }
        std::printf(
            "%s: %zu scans, path %.1f m; ATE rmse %.3f m = %.3f %% of its path (aligned alone), "
            "%.3f m = %.3f %% (one alignment for every robot); loops: %zu in its session, %zu "
            "with another robot's places (%zu false)\n",
            r.name.c_str(), r.frames, path, own.rmse, path > 0 ? 100.0 * own.rmse / path : 0.0,
            shared.rmse, path > 0 ? 100.0 * shared.rmse / path : 0.0, intra, cross, cross_false);
        for (std::size_t o = 0; o < robots.size(); ++o) {
            if (o == k) continue;
            std::vector<mapping::bench::RevisitSegment> seg =
                mapping::bench::cross_revisit_segments(r.reference, robots[o]->reference, a.radius);
            mapping::bench::mark_closed(frames_with_others, &seg);
            auto count_closed = [&seg] {
                return std::size_t(
                    std::count_if(seg.begin(), seg.end(), [](const auto& s) { return s.closed; }));
            };
            const std::size_t at_frames = count_closed();
            mapping::bench::mark_closed_by_local_maps(r.reference, robots[o]->reference,
                                                      r.frame_map, robots[o]->frame_map, a.radius,
                                                      with[o], &seg);
            const std::size_t closed = count_closed();
            std::printf(
                "  revisits of %s's places (within %.1f m): %zu segments, %zu closed (%zu by a "
                "loop at one of their frames, %zu by a loop joining their local maps)\n",
                robots[o]->name.c_str(), a.radius, seg.size(), closed, at_frames,
                closed - at_frames);
            for (const auto& s : seg) {
                if (!s.closed)
                    std::printf("    missed: frames %zu-%zu (%.0f m)\n", s.first, s.last,
                                path_length(common::PoseList(r.reference.begin() + s.first,
                                                             r.reference.begin() + s.last + 1)));
            }
        }
        std::printf("  %s\n", mapper.session_status(r.session).message.c_str());
        for (const mapping::SegmentStatus& s : mapper.segments(r.session)) {
            if (s.segment > 0) std::printf("  %s\n", s.message.c_str());
        }
    }
    std::printf(
        "graph: %zu nodes, %zu edges, %zu connected part(s), %zu part(s) placed together by "
        "loops; %zu loops (%zu false); all robots with one alignment: ATE rmse %.3f m (%zu poses); "
        "final optimisation %s\n",
        mapper.graph().nodes().size(), mapper.graph().edges().size(), final_opt.components,
        mapper.placed_parts(), mapper.loops().size(), false_loops, joint.stats.rmse, joint.stats.n,
        final_opt.solved ? "solved" : final_opt.message.c_str());
    if (!a.out.empty()) {
        std::filesystem::create_directories(a.out);
        for (std::size_t k = 0; k < robots.size(); ++k) {
            common::write_kitti_poses(a.out + "/" + robots[k]->name + "_slam.txt", est[k]);
            common::write_kitti_poses(a.out + "/" + robots[k]->name + "_reference.txt",
                                      robots[k]->reference);
        }
        const map::SaveStats s = map::save_map(a.out + "/map", mapper.snapshot());
        std::printf("map: %s/map, %zu files, %.1f MiB\n", a.out.c_str(), s.files_written,
                    double(s.bytes_total) / 1048576.0);
    }
    return final_opt.solved ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
    Args a;
    CLI::App app{"Several robots mapping one site at once into one map (a simulated scenario)",
                 "ltm_bench_multi_robot"};
    common::cli::configure(app);
    app.add_option("--scenario", a.scenario, "simulator scenario (YAML)")->capture_default_str();
    app.add_option("--sessions", a.sessions,
                   "its sessions driven at once, one a robot (robot1, robot2, ...)")
        ->capture_default_str()
        ->delimiter(',');
    app.add_option("--preset", a.preset, "sensor preset: hdl64, vlp32, vlp16, narrow or os1-64")
        ->capture_default_str();
    app.add_option("--config", a.config, "odometry keys overriding the preset (YAML)");
    app.add_option("--mapping-config", a.mapping_config, "the mapping component's keys (YAML)");
    app.add_option("--max-frames", a.max_frames, "only the first N scans of each robot (0: all)");
    app.add_option("--radius", a.radius, "a revisit: within this distance [m]")
        ->capture_default_str();
    app.add_option("--snapshot-every", a.snapshot_every,
                   "snapshots of the active local maps every N keyframes (0: finished maps only, "
                   "as robot.yaml sends them)")
        ->capture_default_str()
        ->check(CLI::NonNegativeNumber);
    app.add_option("--out", a.out, "write each robot's poses and the map here");
    if (const int code = common::cli::parse(app, argc, argv); code >= 0) return code;
    if (a.sessions.size() < 2) {
        std::cerr << "ltm_bench_multi_robot: --sessions: at least two sessions (robots)\n";
        return 2;
    }
    try {
        return run(a);
    } catch (const std::exception& e) {  // scenarios, configurations, files: one line
        std::cerr << "ltm_bench_multi_robot: " << e.what() << "\n";
    }
    return 1;
}
