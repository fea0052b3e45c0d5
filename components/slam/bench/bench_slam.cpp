// ltm_bench_slam: odometry + mapping (loop closure, pose graph) over a folder of scans. Prints
// ATE before and after loop closure, the loops found (and, with a reference, the revisits closed
// or missed and the false loops), loop detection, verification and optimisation times, memory;
// writes odometry.txt, slam.txt (LiDAR poses, KITTI format), loops.txt, the map and its PLY.
// Also over scans a scenario renders in-process (--scenario, --laps), and --graph-bench N.
// (About 650 lines, one file: the modes share one report and one command line; the scenario
// source, revisit scoring, memory log, lap growth and graph bench are in files of their own.
// run() reads as its steps: configs, source, SlamRun over the frames with the km and lap logs,
// summary, reference, outputs.)
// With --poses (a trajectory from elsewhere: survey, GNSS-INS, another SLAM), the map is built at
// the given poses: no registration, no loop closure; --scenario --true-poses does the same at
// the scenario's true poses. With a reference and --out, T_map_reference.txt is the ATE's
// alignment inverted (the reference frame in the map's: how other scans of the site are scored
// on this map).
// Options: `ltm_bench_slam --help`.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <numeric>
#include <sstream>
#include <string>

#include "common/cli/cli.hpp"
#include "common/core/io_error.hpp"
#include "common/core/kitti_io.hpp"
#include "common/core/ply_io.hpp"
#include "common/core/process_memory.hpp"
#include "common/core/progress.hpp"
#include "common/core/trajectory_io.hpp"
#include "evaluation/core/ate.hpp"
#include "map/core/map_store.hpp"
#include "mapping/bench/revisits.hpp"
#include "mapping/bench/sim_source.hpp"
#include "mapping/core/mapper.hpp"
#include "mapping/params/mapper_params.hpp"
#include "odometry/core/odometry.hpp"
#include "odometry/params/odometry_params.hpp"
#include "slam/bench/graph_bench.hpp"
#include "slam/bench/km_memory.hpp"
#include "slam/bench/lap_growth.hpp"
#include "slam/core/slam_pipeline.hpp"
#include "sources/core/scan_folder.hpp"

namespace {

using namespace ltm;
using Clock = std::chrono::steady_clock;

struct Args {
    std::string dir, out, reference, calib, preset, config, mapping_config, poses;
    std::string pairs, session;
    std::string scenario;  // --scenario: render the scans in-process
    std::size_t laps = 0;
    bool true_poses = false;  // --scenario: the map at the true poses (as --poses)
    std::size_t max_frames = 0, graph_bench = 0, snapshot_every = 10;
};

// Declares the command line on `app`, filling `a`.
void add_options(CLI::App& app, Args& a) {
    namespace cli = common::cli;
    cli::configure(app);
    app.footer(
        "DIR: KITTI layout (velodyne/*.bin) or a PCD/PLY folder (Scans/*.pcd); or --scenario:\n"
        "scans rendered by the simulator (session 0), its true poses as the reference, memory\n"
        "every km; or --graph-bench N: the optimisation of a synthetic graph of N anchors.\n"
        "--poses P: a map from a known trajectory (P: KITTI 3x4 T_world_lidar a scan, camera\n"
        "poses with --calib): the scans placed at those poses, no registration, no loop closure.\n"
        "LTM_BENCH_LOOPS=1 prints every loop and refusal.");
    CLI::Option* dir = app.add_option("DIR", a.dir, "the scans");
    app.add_option("--reference", a.reference,
                   "KITTI-format poses, one a frame (camera poses with --calib)");
    app.add_option("--calib", a.calib,
                   "the reference (and --poses) are in the camera frame of this calib.txt");
    app.add_option("--poses", a.poses,
                   "build the map at these poses (KITTI format, one a scan): no registration, no "
                   "loop closure");
    app.add_option("--out", a.out, "write poses, loops, the map and its PLY here");
    app.add_option("--preset", a.preset, "sensor preset: hdl64, vlp32, vlp16, narrow or os1-64")
        ->default_str("hdl64");
    app.add_option("--config", a.config, "odometry keys overriding the preset (YAML)");
    app.add_option("--mapping-config", a.mapping_config, "the mapping component's keys (YAML)");
    app.add_option("--max-frames", a.max_frames, "only the first N scans (0: all)");
    app.add_option("--snapshot-every", a.snapshot_every,
                   "hand snapshots of the active local maps to the mapper every K keyframes, as "
                   "the odometry component does (0: finished maps only)");
    CLI::Option* pairs = app.add_option(
        "--pairs", a.pairs,
        "verified revisit pairs (hku-avia-2session format): their relative poses are compared "
        "with the ICP-refined ones");
    CLI::Option* session = app.add_option("--session", a.session, "the session of --pairs");
    pairs->needs(session);
    session->needs(pairs);
    CLI::Option* scenario =
        app.add_option("--scenario", a.scenario, "render the scans of this scenario in-process");
    scenario->excludes(dir);
    app.add_option("--laps", a.laps, "drive the route N times (route.laps)")->needs(scenario);
    app.add_flag("--true-poses", a.true_poses,
                 "build the map at the scenario's true poses: no registration, no loop closure "
                 "(as --poses)")
        ->needs(scenario);
    app.add_option("--graph-bench", a.graph_bench,
                   "time the optimisation of a synthetic graph of N anchors");
}

// The rules across options that CLI11 does not state; throws common::cli::UsageError.
void check_options(const Args& a) {
    if (a.dir.empty() && a.scenario.empty() && a.graph_bench == 0)
        throw common::cli::UsageError("DIR", "is required (or --scenario FILE, --graph-bench N)");
    if (!a.scenario.empty() && !a.reference.empty())
        throw common::cli::UsageError("--reference",
                                      "--scenario brings its own reference (the true poses)");
    if (!a.calib.empty() && a.reference.empty() && a.poses.empty())
        throw common::cli::UsageError("--calib", "needs --reference or --poses");
    if (!a.poses.empty() && (a.dir.empty() || a.graph_bench != 0))
        throw common::cli::UsageError("--poses",
                                      "needs a scan folder DIR (not --scenario or "
                                      "--graph-bench)");
}

struct Stats {
    std::vector<double> v;
    const char* unit = "ms";
    void add(double x) { v.push_back(x); }
    std::string str() const {
        if (v.empty()) return "none";
        std::vector<double> s = v;
        std::sort(s.begin(), s.end());
        char buf[160];
        std::snprintf(
            buf, sizeof(buf), "mean %.3f %s  median %.3f  p95 %.3f  max %.3f (%zu)",
            std::accumulate(s.begin(), s.end(), 0.0) / double(s.size()), unit, s[s.size() / 2],
            s[std::min(s.size() - 1, std::size_t(0.95 * double(s.size())))], s.back(), s.size());
        return buf;
    }
};

double ms_since(Clock::time_point t) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
}

// Verified intra-session pairs: "intra sA iA sB iB ... verified T_A_B(12)" (hku-avia-2session).
void report_pairs(const Args& a, const common::PoseList& odom, const common::PoseList& slam) {
    std::ifstream in(a.pairs);
    if (!in) throw common::IoError(a.pairs, "cannot read");
    std::string line;
    Stats err_odom, err_slam;
    err_odom.unit = err_slam.unit = "m";
    std::size_t over = 0;
    while (std::getline(in, line)) {
        std::istringstream f(line);
        std::string kind, sa, sb;
        std::size_t ia = 0, ib = 0;
        double skip = 0;
        int verified = 0;
        if (!(f >> kind >> sa >> ia >> sb >> ib) || kind != "intra" || sa != a.session ||
            sb != a.session)
            continue;
        for (int k = 0; k < 7; ++k) f >> skip;
        f >> verified;
        Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
        for (int r = 0; r < 3; ++r) {
            for (int c = 0; c < 4; ++c) f >> T.matrix()(r, c);
        }
        if (!f || verified != 1 || ia >= slam.size() || ib >= slam.size()) continue;
        const double eo = ((odom[ia].inverse() * odom[ib]).inverse() * T).translation().norm();
        const double es = ((slam[ia].inverse() * slam[ib]).inverse() * T).translation().norm();
        err_odom.add(eo);
        err_slam.add(es);
        over += es > 0.1;
        std::printf("  pair %zu-%zu: odometry off by %.3f m, after loop closure %.3f m\n", ia, ib,
                    eo, es);
    }
    std::printf(
        "verified pairs of %s (relative pose vs ICP, metres): odometry %s; after loop closure %s; "
        "%zu over 0.1 m\n",
        a.session.c_str(), err_odom.str().c_str(), err_slam.str().c_str(), over);
}

// The given trajectory (--poses): one finite rigid pose a scan, for the first `frames` scans;
// camera-frame poses converted with --calib. Throws IoError (one line) otherwise.
common::PoseList read_given_poses(const Args& a, std::size_t frames) {
    common::PoseList poses = common::read_kitti_poses(a.poses);
    if (poses.size() < frames) {
        throw common::IoError(a.poses, std::to_string(poses.size()) + " poses for " +
                                           std::to_string(frames) +
                                           " scans: one pose a scan is needed");
    }
    poses.resize(frames);
    for (std::size_t i = 0; i < frames; ++i) {
        Eigen::Isometry3d& T = poses[i];
        const Eigen::Matrix3d R = T.linear();
        if (!T.matrix().allFinite() ||
            (R.transpose() * R - Eigen::Matrix3d::Identity()).norm() > 1e-3 ||
            R.determinant() <= 0.0) {
            throw common::IoError(a.poses, "pose " + std::to_string(i) + " (the pose of scan " +
                                               std::to_string(i) +
                                               ") is not a finite rigid transform");
        }
        T.linear() = Eigen::Quaterniond(R).normalized().toRotationMatrix();  // printed digits
    }
    if (!a.calib.empty())
        poses = common::camera_to_lidar_poses(poses, common::read_kitti_calib_tr(a.calib));
    return poses;
}

int graph_bench(std::size_t anchors) {
    const mapping::MapperConfig config;
    slam::bench::run_graph_bench(std::min<std::size_t>(anchors, 100), config, 7);  // warm up
    const slam::bench::GraphBenchResult r = slam::bench::run_graph_bench(anchors, config);
    std::printf("graph: %zu anchors, %zu edges (%zu loops)%s\n", r.nodes, r.edges, r.loops,
                r.solved ? "" : " NOT SOLVED");
    std::printf(
        "optimisation: first %.1f ms (from the odometry; %d solves, %d iterations), "
        "incremental %.1f ms (one more loop); loops rejected %zu\n",
        r.first_ms, r.solves, r.iterations, r.incremental_ms, r.loops_rejected);
    std::printf("largest anchor error: %.2f m before, %.3f m after\n", r.error_before,
                r.error_after);
    return r.solved ? 0 : 1;
}

odometry::OdometryConfig odometry_config(const Args& a) {
    return a.config.empty() ? odometry::preset_config(common::parse_sensor_preset(
                                  a.preset.empty() ? "hdl64" : a.preset))
                            : odometry::load_odometry_config_file(a.config);
}

// The mapping component's keys and presets (a file's `mapping:` section or top level).
mapping::MapperConfig mapper_config(const Args& a) {
    return a.mapping_config.empty() ? mapping::mapper_preset(common::parse_sensor_preset(
                                          a.preset.empty() ? "hdl64" : a.preset))
                                    : mapping::load_mapper_config_file(a.mapping_config, a.preset);
}

// The scans: a folder, or a scenario rendered in-process.
struct ScanSource {
    std::unique_ptr<sources::ScanFolder> folder;
    std::unique_ptr<mapping::bench::SimSource> sim;
    std::size_t available = 0;
    const char* kind = "simulated";
    common::PointCloud load(std::size_t i) const { return sim ? sim->load(i) : folder->load(i); }
};

// Prints the scenario's description.
ScanSource open_source(const Args& a) {
    ScanSource s;
    if (a.scenario.empty()) {
        sources::ScanFolderConfig folder;
        folder.path = a.dir;
        folder.format = sources::ScanFormat::kAuto;
        s.folder = std::make_unique<sources::ScanFolder>(folder);
        s.kind = s.folder->format() == sources::ScanFormat::kKittiBin ? "kitti" : "pcd";
        s.available = s.folder->size();
    } else {
        mapping::bench::SimSourceOptions so;
        so.scenario = a.scenario;
        so.laps = int(a.laps);
        s.sim = std::make_unique<mapping::bench::SimSource>(so);
        s.available = s.sim->size();
        std::printf("%s\n", s.sim->describe().c_str());
    }
    return s;
}

// The poses of the first n frames in the world (the odometry's where the mapper has none).
common::PoseList world_poses(const mapping::Mapper& mapper, const common::PoseList& odom,
                             const std::vector<std::uint64_t>& frame_map, std::size_t n) {
    common::PoseList est(n);
    for (std::size_t j = 0; j < n; ++j) {
        const std::optional<Eigen::Isometry3d> w = mapper.T_world_lidar(frame_map[j], odom[j]);
        est[j] = w ? *w : odom[j];
    }
    return est;
}

// The odometry's path over the first n frames [m].
double odometry_path(const common::PoseList& odom, std::size_t n) {
    double path = 0.0;
    for (std::size_t j = 1; j < n; ++j)
        path += (odom[j].translation() - odom[j - 1].translation()).norm();
    return path;
}

void report_maps(const std::vector<common::LocalMapData>& maps,
                 const std::vector<mapping::LocalMapResult>& results) {
    for (std::size_t k = 0; k < results.size(); ++k) {
        if (!results[k].added && maps[k].finished)
            std::fprintf(stderr, "local map %lu: %s\n", (unsigned long)maps[k].id,
                         results[k].message.c_str());
    }
}

// The pipeline over the scans, and what the bench keeps of every frame.
struct SlamRun {
    SlamRun(const Args& a, const odometry::OdometryConfig& oc, const mapping::MapperConfig& mc,
            std::size_t frames)
        : pipeline(pipeline_config(a, oc, mc)),
          mapper(pipeline.mapper()),
          scan_context(mc.scan_context),
          shadow(mc.scan_context, mc.loop_detection),
          odom(frames),
          frame_map(frames, 0) {}

    static slam::SlamPipelineConfig pipeline_config(const Args& a,
                                                    const odometry::OdometryConfig& oc,
                                                    const mapping::MapperConfig& mc) {
        slam::SlamPipelineConfig pc;
        pc.odometry = oc;
        pc.mapping = mc;
        pc.handover.snapshot_every_keyframes = int(a.snapshot_every);
        return pc;
    }

    // Scan i through the pipeline (at its given pose, if any), recorded.
    void process(std::size_t i, const common::PointCloud& cloud, const Eigen::Isometry3d* given) {
        const slam::SlamFrame f = given ? pipeline.process(cloud, *given) : pipeline.process(cloud);
        const odometry::FrameResult& r = f.odometry;
        odometry_ms.add(f.odometry_ms);
        odom[i] = r.T_odom_lidar;
        frame_map[i] = r.local_map_id;
        if (i) path_so_far += (odom[i].translation() - odom[i - 1].translation()).norm();
        if (!r.message.empty()) std::fprintf(stderr, "frame %zu: %s\n", i, r.message.c_str());
        if (f.keyframe && given) {
            add.add(f.keyframe_ms);
            ++keyframes;
        } else if (f.keyframe) {
            record_keyframe(i, f);
        }
        if (f.optimisation) {
            optimise.add(f.optimise_ms);
            ++optimisations;
            if (!f.optimisation->solved)
                std::fprintf(stderr, "optimisation failed: %s\n", f.optimisation->message.c_str());
        }
        report_maps(f.handover.local_maps, f.local_maps);
    }

    // A keyframe's loop detection (timed alone on the shadow detector), verification, refusals.
    void record_keyframe(std::size_t i, const slam::SlamFrame& f) {
        const common::KeyframeData& k = *f.handover.keyframe;
        const mapping::KeyframeResult& kr = *f.keyframe;
        auto t0 = Clock::now();
        std::vector<mapping::LoopCandidate> c;
        shadow.add(places::make_scan_context(k.points, scan_context), 0, k.stamp, &c);
        const double detection = ms_since(t0);
        detect.add(detection);
        add.add(f.keyframe_ms);
        ++keyframes;
        candidates += kr.candidates;
        rejected += kr.rejected.size();
        for (const mapping::LoopRejection& j : kr.rejected) {
            if (std::getenv("LTM_BENCH_LOOPS")) {
                std::printf("  refused %zu -> %lu (distance %.3f): %s\n", i,
                            (unsigned long)mapper.keyframes()[j.match_keyframe]->data.scan_index,
                            j.descriptor_distance, j.reason.c_str());
            }
            std::string why = j.reason.substr(0, j.reason.find_first_of("0123456789"));
            ++reasons[why];
        }
        if (kr.verified) {
            ++verifications;
            verify.add(std::max(0.0, f.keyframe_ms - detection));
        }
    }

    slam::SlamPipeline pipeline;
    const mapping::Mapper& mapper;
    places::ScanContextConfig scan_context;
    mapping::LoopDetector shadow;  // detection timing alone
    const Clock::time_point t_start = Clock::now();
    common::PoseList odom;
    std::vector<std::uint64_t> frame_map;
    double path_so_far = 0.0;  // [m] odometry path
    Stats detect, add, verify, optimise, odometry_ms;
    std::size_t keyframes = 0, candidates = 0, verifications = 0, rejected = 0;
    std::size_t optimisations = 0;               // since the last lap sample
    std::map<std::string, std::size_t> reasons;  // refusals by reason (numbers cut off)
};

void log_km(const SlamRun& run, std::size_t i, slam::bench::KmMemoryLog* km_log) {
    if (!km_log->due(run.path_so_far)) return;
    slam::bench::KmSample s;
    s.km = run.path_so_far / 1000.0;
    s.frame = i;
    s.mapper_mib = double(run.mapper.memory_bytes()) / 1048576.0;
    s.process = common::process_memory();
    s.local_maps = run.mapper.local_map_count();
    s.keyframes = run.keyframes;
    s.loops = run.mapper.loops().size();
    km_log->add(s, stdout);
}

// --laps N > 1: the map's growth and quality at the end of every lap.
struct LapLog {
    LapLog(const Args& a, const ScanSource& source)
        : writer(a.laps > 1 && !a.out.empty() ? std::make_unique<map::MapWriter>(a.out + "/map")
                                              : nullptr),
          sim_ref(source.sim ? source.sim->reference() : common::PoseList()),
          lap_end(a.laps > 1 ? slam::bench::lap_ends(sim_ref, a.laps)
                             : std::vector<std::size_t>()) {}

    void sample(SlamRun& run, std::size_t i, std::size_t frames) {
        if (log.samples().size() >= lap_end.size() ||
            (i != lap_end[log.samples().size()] && i + 1 != frames))
            return;
        const mapping::Mapper& mapper = run.mapper;
        slam::bench::LapSample s;
        s.lap = log.samples().size() + 1;
        s.frame = i;
        s.mapper_mib = double(mapper.memory_bytes()) / 1048576.0;
        if (writer) s.disk_mib = double(writer->save(mapper.snapshot()).bytes_total) / 1048576.0;
        s.local_maps = mapper.local_map_count();
        s.keyframes = mapper.keyframes().size();
        s.nodes = mapper.graph().nodes().size();
        s.edges = mapper.graph().edges().size();
        s.loops = mapper.loops().size();
        s.optimisations = run.optimisations;
        s.optimise_p95_ms = slam::bench::p95(std::vector<double>(
            run.optimise.v.end() - std::ptrdiff_t(run.optimisations), run.optimise.v.end()));
        run.optimisations = 0;
        quality(run, i, &s);
        log.add(s, stdout);
    }

    // ATE and revisits over frames 0..last (the laps so far), as scored at the end.
    void quality(const SlamRun& run, std::size_t last, slam::bench::LapSample* s) const {
        if (sim_ref.size() <= last) return;
        const common::PoseList est = world_poses(run.mapper, run.odom, run.frame_map, last + 1);
        const common::PoseList ref(sim_ref.begin(), sim_ref.begin() + last + 1);
        const double path = odometry_path(run.odom, last + 1);
        s->ate_rmse = eval::compute_ate(est, ref).rmse;
        s->ate_percent = path > 0.0 ? 100.0 * s->ate_rmse / path : 0.0;
        std::vector<std::size_t> queries;
        for (const mapping::LoopClosure& l : run.mapper.loops()) {
            if (l.query_scan <= last) queries.push_back(l.query_scan);
        }
        std::vector<mapping::bench::RevisitSegment> seg =
            mapping::bench::revisit_segments(ref, 5.0, 300);
        mapping::bench::mark_closed(queries, &seg);
        s->revisits = seg.size();
        s->revisits_closed =
            std::count_if(seg.begin(), seg.end(), [](const auto& r) { return r.closed; });
        s->longest_unclosed = mapping::bench::longest_unclosed_run(seg, queries);
    }

    slam::bench::LapGrowthLog log;
    std::unique_ptr<map::MapWriter> writer;
    const common::PoseList sim_ref;          // the reference to score each lap against
    const std::vector<std::size_t> lap_end;  // the last frame of each lap
};

// The counts, loops, segments, timings and memory of the run.
void print_summary(const SlamRun& run, std::size_t frames, bool given, double path, double final_ms,
                   const mapping::OptimisationSummary& final_opt) {
    const mapping::Mapper& mapper = run.mapper;
    std::size_t active = 0;
    for (const map::PoseGraphEdge& e : mapper.graph().edges()) {
        active += e.kind == map::EdgeKind::kLoop && e.active;
    }
    std::printf(
        "keyframes %zu (%zu stored), local maps %zu, graph %zu nodes %zu edges; path %.1f m\n",
        run.keyframes, mapper.keyframes().size(), mapper.local_map_count(),
        mapper.graph().nodes().size(), mapper.graph().edges().size(), path);
    std::printf("%zu scans in %.1f s (%s)\n", frames, ms_since(run.t_start) / 1000.0,
                given ? "placed at the given poses" : "odometry and mapping");
    std::printf(
        "loops: %zu closed (%zu kept by the last optimisation), %zu candidates, %zu verifications, "
        "%zu refused\n",
        mapper.loops().size(), active, run.candidates, run.verifications, run.rejected);
    for (const auto& [why, n] : run.reasons) std::printf("  refused %zu: %s...\n", n, why.c_str());
    const std::size_t from_graph =
        std::count_if(mapper.loops().begin(), mapper.loops().end(),
                      [](const mapping::LoopClosure& l) { return l.from_graph_guess; });
    std::printf("  verified from the graph's estimate %zu, from the descriptor's guess %zu\n",
                from_graph, mapper.loops().size() - from_graph);
    // Odometry segments (the odometry lost track and restarted): joined by a loop or not.
    const std::vector<mapping::SegmentStatus> segments = mapper.segments();
    const std::size_t across =
        std::count_if(mapper.loops().begin(), mapper.loops().end(),
                      [](const mapping::LoopClosure& l) { return l.across_break; });
    std::printf("odometry segments %zu, loops across a break %zu\n", segments.size(), across);
    for (const mapping::SegmentStatus& s : segments) {
        if (s.segment > 0) std::printf("  %s\n", s.message.c_str());
    }
    std::printf("odometry a frame: %s\n", run.odometry_ms.str().c_str());
    std::printf("loop detection a keyframe (descriptor + retrieval): %s\n",
                run.detect.str().c_str());
    std::printf("mapping a keyframe (detection + verification): %s\n", run.add.str().c_str());
    std::printf("verification a verified keyframe: %s\n", run.verify.str().c_str());
    std::printf("optimisation after a loop: %s; final %.1f ms (%s)\n", run.optimise.str().c_str(),
                final_ms, final_opt.message.c_str());
    const double mib = double(mapper.memory_bytes()) / 1048576.0;
    std::printf("memory: mapper %.1f MiB (%.1f MiB/km), peak resident %.1f MiB\n", mib,
                path > 0 ? mib / (path / 1000.0) : 0.0, common::process_memory().peak_mib);
}

// The loops against the reference: false ones printed and counted; the query scans of the
// right ones into *queries.
std::size_t score_loops(const mapping::Mapper& mapper, const common::PoseList& ref,
                        std::vector<std::size_t>* queries) {
    std::size_t false_loops = 0;
    for (const mapping::LoopClosure& l : mapper.loops()) {
        if (l.query_scan >= ref.size() || l.match_scan >= ref.size()) continue;
        const Eigen::Isometry3d e =
            (ref[l.match_scan].inverse() * ref[l.query_scan]).inverse() * l.T_match_query;
        const bool bad = e.translation().norm() > 1.0 ||
                         Eigen::AngleAxisd(e.linear()).angle() > 5.0 * M_PI / 180;
        false_loops += bad;
        if (std::getenv("LTM_BENCH_LOOPS")) {
            std::printf(
                "  loop %lu -> %lu: err %.2f m, inl %zu frac %.2f rms %.3f, structure %zu/%zu "
                "= %.2f, "
                "moved %.2f m, disagreed %.2f m%s\n",
                (unsigned long)l.query_scan, (unsigned long)l.match_scan, e.translation().norm(),
                l.inliers, l.inlier_fraction, l.inlier_rms, l.structure_inliers, l.structure_points,
                l.structure_points ? double(l.structure_inliers) / l.structure_points : 0.0,
                l.correction_translation, l.disagreement,
                l.from_graph_guess ? " (graph's guess)" : "");
        }
        if (bad) {
            std::printf(
                "  false loop: scan %lu -> %lu, off by %.2f m (inliers %zu, %.2f, rms %.3f m, "
                "moved %.2f m from the guess, disagreed %.2f m with the graph)\n",
                (unsigned long)l.query_scan, (unsigned long)l.match_scan, e.translation().norm(),
                l.inliers, l.inlier_fraction, l.inlier_rms, l.correction_translation,
                l.disagreement);
        } else {
            queries->push_back(l.query_scan);
        }
    }
    return false_loops;
}

// ATE before and after loop closure, false loops, revisits closed and missed.
void report_reference(const Args& a, const ScanSource& source, std::size_t frames,
                      const SlamRun& run, const common::PoseList& slam, double path) {
    common::PoseList ref =
        source.sim ? source.sim->reference() : common::read_kitti_poses(a.reference);
    if (!a.calib.empty())
        ref = common::camera_to_lidar_poses(ref, common::read_kitti_calib_tr(a.calib));
    ref.resize(std::min(ref.size(), frames));
    const eval::AteResult before = eval::compute_ate(run.odom, ref);
    const eval::AteDetail detail = eval::compute_ate_detail(slam, ref);
    const eval::AteResult& after = detail.stats;
    if (!a.out.empty()) {
        // The reference's frame in the map's (the ATE's alignment, inverted): what scores other
        // scans of the site (their reference) on this map (ltm_bench_localise
        // --reference-transform).
        std::filesystem::create_directories(a.out);
        common::write_kitti_poses(a.out + "/T_map_reference.txt",
                                  common::PoseList{detail.T_ref_est.inverse()});
    }
    std::printf(
        "ATE (SE(3)-aligned, %zu poses): odometry rmse %.3f m (max %.3f), after loop closure "
        "rmse %.3f m (max %.3f) = %.3f %% of the path\n",
        after.n, before.rmse, before.max, after.rmse, after.max,
        path > 0 ? 100.0 * after.rmse / path : 0.0);
    std::vector<std::size_t> queries;
    const std::size_t false_loops = score_loops(run.mapper, ref, &queries);
    // Revisits: within 5 m of a pose at least 30 s (300 frames at 10 Hz) earlier.
    std::vector<mapping::bench::RevisitSegment> seg =
        mapping::bench::revisit_segments(ref, 5.0, 300);
    mapping::bench::mark_closed(queries, &seg);
    const std::size_t closed =
        std::count_if(seg.begin(), seg.end(), [](const auto& s) { return s.closed; });
    std::printf(
        "revisits (within 5 m of a pose 300+ frames earlier): %zu segments, %zu closed; "
        "false loops %zu\n",
        seg.size(), closed, false_loops);
    for (const auto& s : seg) {
        if (!s.closed) std::printf("  missed revisit: frames %zu-%zu\n", s.first, s.last);
    }
}

// --out: the poses, the loops, the map and its PLY.
void write_outputs(const Args& a, const mapping::Mapper& mapper, const common::PoseList& odom,
                   const common::PoseList& slam, double path, map::MapWriter* lap_writer) {
    std::filesystem::create_directories(a.out);
    common::write_kitti_poses(a.out + "/odometry.txt", odom);
    common::write_kitti_poses(a.out + "/slam.txt", slam);
    std::ofstream loops(a.out + "/loops.txt");
    loops << "# query_scan match_scan T_match_query (3x4 row-major: query LiDAR frame -> match "
             "LiDAR frame)\n";
    for (const mapping::LoopClosure& l : mapper.loops()) {
        loops << l.query_scan << " " << l.match_scan << " "
              << common::format_kitti_pose(l.T_match_query) << "\n";
    }
    const auto t0 = Clock::now();
    const map::SaveStats s = lap_writer ? lap_writer->save(mapper.snapshot())
                                        : map::save_map(a.out + "/map", mapper.snapshot());
    std::printf("map: %s/map, %zu files, %.1f MiB (%.1f MiB/km), saved in %.0f ms\n", a.out.c_str(),
                s.files_written, double(s.bytes_total) / 1048576.0,
                path > 0 ? double(s.bytes_total) / 1048576.0 / (path / 1000.0) : 0.0, ms_since(t0));
    map::GlobalMapStats gs;
    common::write_ply(a.out + "/global_map.ply", mapper.global_map(&gs));
    std::printf("global map: %zu voxels fused from %zu -> %s/global_map.ply\n", gs.fused_voxels,
                gs.input_voxels, a.out.c_str());
}

int run(const Args& a) {
    const odometry::OdometryConfig oc = odometry_config(a);
    mapping::MapperConfig mc = mapper_config(a);
    const ScanSource source = open_source(a);
    const std::size_t frames =
        a.max_frames ? std::min(a.max_frames, source.available) : source.available;
    std::printf("%s: %zu %s scans, odometry voxel %.2f m\n",
                (a.scenario.empty() ? a.dir : a.scenario).c_str(), frames, source.kind,
                oc.voxel_size);
    const bool given = !a.poses.empty() || a.true_poses;
    common::PoseList given_poses;
    if (a.true_poses) {
        given_poses = source.sim->reference();
        given_poses.resize(frames);
    } else if (given) {
        given_poses = read_given_poses(a, frames);
    }
    if (given) {
        mc.loop_closure = false;  // the poses are final
        std::printf(
            "map built from given poses (%s): scans placed at them, no registration, no loop "
            "closure\n",
            a.true_poses ? "the scenario's true poses" : a.poses.c_str());
    }
    slam::bench::KmMemoryLog km_log;
    LapLog laps(a, source);
    SlamRun slam_run(a, oc, mc, frames);
    common::Progress progress("slam", frames);
    for (std::size_t i = 0; i < frames; ++i) {
        slam_run.process(i, source.load(i), given ? &given_poses[i] : nullptr);
        log_km(slam_run, i, &km_log);
        laps.sample(slam_run, i, frames);
        progress.update(i + 1);
    }
    progress.finish();
    const auto t0 = Clock::now();
    std::vector<mapping::LocalMapResult> last;
    const mapping::OptimisationSummary final_opt = slam_run.pipeline.finish(&last);
    const double final_ms = ms_since(t0);

    const common::PoseList slam =
        world_poses(slam_run.mapper, slam_run.odom, slam_run.frame_map, frames);
    const double path = odometry_path(slam_run.odom, frames);
    print_summary(slam_run, frames, given, path, final_ms, final_opt);
    km_log.report(stdout);
    laps.log.report(stdout);
    if (!a.reference.empty() || source.sim)
        report_reference(a, source, frames, slam_run, slam, path);
    if (!a.pairs.empty()) report_pairs(a, slam_run.odom, slam);
    if (!a.out.empty())
        write_outputs(a, slam_run.mapper, slam_run.odom, slam, path, laps.writer.get());
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    Args args;
    CLI::App app{
        "Odometry + mapping (loop closure, pose graph) over a folder of scans or a "
        "simulated scenario",
        "ltm_bench_slam"};
    add_options(app, args);
    if (const int code = common::cli::parse(app, argc, argv); code >= 0) return code;
    try {
        check_options(args);
    } catch (const common::cli::UsageError& e) {
        return common::cli::usage_error(app, e);
    }
    try {
        return args.graph_bench ? graph_bench(args.graph_bench) : run(args);
    } catch (const std::exception& e) {  // files, configurations, scenarios, maps: one line
        std::cerr << "ltm_bench_slam: " << e.what() << "\n";
    }
    return 1;
}
