// ltm_bench_maintenance: sessions of scans at given poses, in order, on one maintained map
// (METHOD.md section 5). Writes what the DynamicMap benchmark expects of a method:
//   OUT/cleaned_map.ply  the scans' own points (within max_range) that the maintained map keeps,
//                        in the world frame of the poses (LiDAR frame of the first scan for
//                        camera poses converted with --calib);
//   OUT/removed.ply      the points it removed;
//   OUT/cleaned_map_sN.ply  with several sessions: session N's points that the map keeps;
//   OUT/changes.txt      per session: segments removed (moving, vanished) and added (new);
//   OUT/changes_sN.ply   the voxels each session removed (red) and added (green), as the
//                        component writes them (maintenance/core/change_report.hpp).
// and prints per session the time, views, voxels, memory and the changes, so that
//   ltm_eval dynamic --map OUT/cleaned_map.ply --scans DIR ... scores it.
// Options: `ltm_bench_maintenance --help`.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "common/cli/cli.hpp"
#include "common/cli/config_set.hpp"
#include "common/core/config_check.hpp"
#include "common/core/io_error.hpp"
#include "common/core/kitti_io.hpp"
#include "common/core/ply_io.hpp"
#include "common/core/process_memory.hpp"
#include "common/core/progress.hpp"
#include "common/core/trajectory_io.hpp"
#include "maintenance/core/change_report.hpp"
#include "maintenance/core/long_term_map.hpp"
#include "sources/core/scan_folder.hpp"

namespace {

using namespace ltm;
using Clock = std::chrono::steady_clock;

struct Args {
    std::vector<std::string> sessions, poses, set;
    std::string calib, out, preset = "default";
    std::string map;  // a saved maintained map to start from (the sessions continue it)
    double pass_every =
        0.0;  // [s] of scan time: a pass this often, as the component (0: at the end)
    std::vector<float> inspect;  // x y z: print the histories of the voxels there
    std::size_t first = 0, count = 0, every = 1;
    bool save = false;  // save the map after every session (OUT/long_term_map.bin)
};

// The defaults: the time-dependent thresholds follow each session's span and views
// (maintenance/core/derived_thresholds.hpp), so a one-second window and a session of minutes
// need no preset. `--preset short` (a window of a second or two) is kept as an alias of them for
// the command lines written before.
maintenance::MaintenanceConfig make_config(const Args& a) {
    maintenance::MaintenanceConfig c;
    common::cli::apply_config_sets(c, a.set, "MaintenanceConfig", "change.sigma");
    return c;
}

// The histories and verdicts of the voxels within 0.4 m of `at`, as the next pass judges them.
void print_voxels_at(const maintenance::LongTermMap& map, const std::vector<float>& at_xyz) {
    const Eigen::Vector3f at(at_xyz[0], at_xyz[1], at_xyz[2]);
    for (const Eigen::Vector3f& p : map.voxel_centres()) {
        if ((p - at).norm() > 0.4f) continue;
        const maintenance::ObservedVoxel& v = *map.voxel_at(p);
        const maintenance::VoxelJudgement j =
            maintenance::judge_voxel(map.decision_config().change, map.config().slot, v);
        std::printf(
            "voxel %.2f %.2f %.2f: verdict %d score %.2f views %u hits %u recent %u/%u\n  hits:",
            p.x(), p.y(), p.z(), int(j.verdict), j.score, j.views, j.hits, j.recent_hits,
            j.recent_views);
        for (const auto& e : v.hit_histogram()) std::printf(" %d:%d", e.slot, e.count);
        std::printf("\n  free:");
        for (const auto& e : v.free_histogram()) std::printf(" %d:%d", e.slot, e.count);
        std::printf("\n");
    }
}

// After a pass: the voxels kept within 0.4 m of `at` and the segment each belongs to (its
// voxels and their extent): a moving voxel kept with a large segment stayed with it.
void print_segments_at(const maintenance::LongTermMap& map, const std::vector<float>& at_xyz) {
    const Eigen::Vector3f at(at_xyz[0], at_xyz[1], at_xyz[2]);
    const std::vector<Eigen::Vector3f> centres = map.voxel_centres();
    for (const Eigen::Vector3f& p : centres) {
        if ((p - at).norm() > 0.4f) continue;
        const maintenance::ObservedVoxel& v = *map.voxel_at(p);
        if (v.segment == 0) {
            std::printf("kept %.2f %.2f %.2f: %s\n", p.x(), p.y(), p.z(),
                        v.flags & maintenance::kGround ? "ground" : "no segment");
            continue;
        }
        std::size_t n = 0;
        Eigen::Vector3f lo = p, hi = p;
        for (const Eigen::Vector3f& q : centres) {  // the same segment of the same region
            if ((q - p).head<2>().cwiseAbs().maxCoeff() > map.config().region_size) continue;
            const maintenance::ObservedVoxel& w = *map.voxel_at(q);
            if (w.segment != v.segment || (w.flags & maintenance::kGround)) continue;
            ++n;
            lo = lo.cwiseMin(q);
            hi = hi.cwiseMax(q);
        }
        std::printf(
            "kept %.2f %.2f %.2f: segment %u, %zu voxels from (%.1f %.1f %.1f) to "
            "(%.1f %.1f %.1f)\n",
            p.x(), p.y(), p.z(), v.segment, n, lo.x(), lo.y(), lo.z(), hi.x(), hi.y(), hi.z());
    }
}

int run(const Args& a) {
    const maintenance::MaintenanceConfig config = make_config(a);
    maintenance::LongTermMap map = a.map.empty() ? maintenance::LongTermMap(config)
                                                 : maintenance::LongTermMap::load(a.map, config);
    // A loaded map's sessions go on: this run's first session is the next one.
    const std::uint32_t first_session = map.sessions().empty() ? 0 : map.sessions().back() + 1;
    if (!a.map.empty())
        std::printf("map %s: %zu voxels of %zu sessions\n", a.map.c_str(), map.stats().voxels,
                    map.sessions().size());
    if (!a.poses.empty() && a.poses.size() != a.sessions.size())
        throw common::cli::UsageError(std::to_string(a.poses.size()) + " --poses for " +
                                      std::to_string(a.sessions.size()) + " --sessions");
    std::filesystem::create_directories(a.out);
    // Each session's folder and poses (T_world_lidar).
    std::vector<sources::ScanFolder> folders;
    std::vector<common::PoseList> poses;
    for (std::size_t s = 0; s < a.sessions.size(); ++s) {
        sources::ScanFolderConfig fc;
        fc.path = a.sessions[s];
        fc.start = a.first;
        fc.count = a.count;
        folders.emplace_back(fc);
        std::string p = a.poses.empty() ? "" : a.poses[s];
        if (p.empty()) {
            const std::string seq = common::kitti_sequence_dir(a.sessions[s]);
            p = (std::filesystem::path(seq) / "poses.txt").string();
        }
        common::PoseList list = common::read_kitti_poses(p);
        if (!a.calib.empty())
            list = common::camera_to_lidar_poses(list, common::read_kitti_calib_tr(a.calib));
        if (list.size() < a.first + folders.back().size())
            throw common::IoError(p, std::to_string(list.size()) + " poses for scans up to " +
                                         std::to_string(a.first + folders.back().size()));
        poses.push_back(std::move(list));
    }

    std::ofstream changes(std::filesystem::path(a.out) / "changes.txt");
    const auto t_all = Clock::now();
    std::size_t scans = 0, passes = 0;
    for (std::size_t s = 0; s < folders.size(); ++s) {
        const sources::ScanFolder& f = folders[s];
        const auto t0 = Clock::now();
        map.begin_session(first_session + std::uint32_t(s), f.size() ? f.stamp(0) : 0.0);
        common::Progress progress("session " + std::to_string(s), f.size(), "scans");
        double last_pass = f.size() ? f.stamp(0) : 0.0;
        std::size_t removed_in_passes = 0;
        for (std::size_t i = 0; i < f.size(); ++i) {
            const common::PointCloud cloud = f.load(i);
            map.add_scan(cloud.points, poses[s][a.first + i], f.stamp(i));
            progress.update(i + 1);
            if (a.pass_every > 0.0 && f.stamp(i) - last_pass >= a.pass_every) {
                // as the component: a pass over the regions judged so far, views still pending
                last_pass = f.stamp(i);
                if (a.inspect.size() == 3) print_voxels_at(map, a.inspect);
                const maintenance::ChangeSet c = map.maintain();
                removed_in_passes += c.voxels_removed;
                maintenance::write_change_summary(changes, c, passes++);
            }
        }
        progress.finish();
        const double add_s = std::chrono::duration<double>(Clock::now() - t0).count();
        if (a.inspect.size() == 3) {
            map.flush_views();
            print_voxels_at(map, a.inspect);
        }
        const maintenance::MaintenanceConfig used = map.decision_config();
        const maintenance::ChangeSet c = map.end_session();
        scans += f.size();
        if (a.pass_every > 0.0)
            std::printf("session %zu: the passes during the session removed %zu voxels\n", s,
                        removed_in_passes);
        if (a.inspect.size() == 3) print_segments_at(map, a.inspect);
        std::printf(
            "session %zu thresholds (from its span and views unless --set): view_spacing %.3f s "
            "(at the end), sigma %.3f s, static_span %.3f s, min_views %d, changed_score %.2f, "
            "free_dominant %.2f\n",
            s, *used.view_spacing, *used.change.sigma, *used.change.static_span,
            *used.change.min_views, *used.change.changed_score, *used.change.free_dominant);
        const maintenance::LongTermMapStats st = map.stats();
        std::printf(
            "session %zu: %zu scans in %.1f s (%.1f scans/s; views judged voxels for %.1f s), "
            "maintenance %.0f ms over %zu regions (%.1f ms a region)\n",
            s, f.size(), add_s, f.size() / std::max(add_s, 1e-9), st.judge_ms / 1000.0, c.time_ms,
            st.regions, c.time_ms / std::max<std::size_t>(1, st.regions));
        std::printf(
            "  motion tracker (so far): %.1f s, %zu clusters, %zu compared, %zu moving pairs, "
            "%zu voxels flagged moving\n",
            st.motion_ms / 1000.0, st.motion.clusters, st.motion.compared, st.motion.moving,
            st.voxels_flagged_moving);
        std::printf(
            "  removed: %zu moving, %zu vanished segments (%zu + %zu voxels); new: %zu; "
            "map %zu voxels, %.1f MiB\n",
            c.count(maintenance::ChangeReason::kMoving),
            c.count(maintenance::ChangeReason::kVanished),
            c.removed_voxels_by(maintenance::ChangeReason::kMoving),
            c.removed_voxels_by(maintenance::ChangeReason::kVanished),
            c.count(maintenance::ChangeReason::kNew), st.voxels, st.memory_bytes / 1048576.0);
        std::printf("  state: %.1f B a voxel in memory",
                    double(st.memory_bytes) / double(std::max<std::size_t>(1, st.voxels)));
        if (a.save) {
            const std::string file = (std::filesystem::path(a.out) / "long_term_map.bin").string();
            const auto ts = Clock::now();
            map.save(file);
            const double save_s = std::chrono::duration<double>(Clock::now() - ts).count();
            const auto bytes = std::filesystem::file_size(file);
            std::printf(", saved %.1f MiB (%.1f B a voxel) in %.2f s", bytes / 1048576.0,
                        double(bytes) / double(std::max<std::size_t>(1, st.voxels)), save_s);
        }
        std::printf("\n");
        maintenance::write_change_summary(changes, c, passes++);
        maintenance::write_change_ply(
            (std::filesystem::path(a.out) / ("changes_s" + std::to_string(s) + ".ply")).string(),
            c);
    }
    // The scans' own points, kept or removed by the final map (all sessions, and each session).
    common::PlyCloud kept, removed;
    const float max_range = float(config.max_range);
    for (std::size_t s = 0; s < folders.size(); ++s) {
        const sources::ScanFolder& f = folders[s];
        common::PlyCloud kept_here;
        for (std::size_t i = 0; i < f.size(); i += a.every) {
            const common::PointCloud cloud = f.load(i);
            const Eigen::Isometry3f T = poses[s][a.first + i].cast<float>();
            for (const Eigen::Vector3f& p : cloud.points) {
                if (!p.allFinite() || p.norm() > max_range) continue;
                const Eigen::Vector3f w = T * p;
                if (map.keeps(w)) {
                    kept.points.push_back(w);
                    kept_here.points.push_back(w);
                } else {
                    removed.points.push_back(w);
                }
            }
        }
        if (folders.size() > 1)
            common::write_ply(
                (std::filesystem::path(a.out) / ("cleaned_map_s" + std::to_string(s) + ".ply"))
                    .string(),
                kept_here);
    }
    common::write_ply((std::filesystem::path(a.out) / "cleaned_map.ply").string(), kept);
    common::write_ply((std::filesystem::path(a.out) / "removed.ply").string(), removed);
    const double total_s = std::chrono::duration<double>(Clock::now() - t_all).count();
    const common::ProcessMemory mem = common::process_memory();
    std::printf(
        "%zu sessions, %zu scans in %.1f s; kept %zu points, removed %zu; peak memory "
        "%.0f MiB\nwrote %s/{cleaned_map.ply, removed.ply, changes.txt, changes_s*.ply}\n",
        folders.size(), scans, total_s, kept.points.size(), removed.points.size(), mem.peak_mib,
        a.out.c_str());
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Map maintenance over sessions of scans at given poses, on one map",
                 "ltm_bench_maintenance"};
    Args a;
    common::cli::configure(app);
    app.add_option("--sessions", a.sessions, "scan folders (KITTI layout), in order")
        ->required()
        ->expected(1, 1000);
    app.add_option("--poses", a.poses,
                   "KITTI-format poses, one file a session (default: DIR's sequence poses.txt)")
        ->expected(1, 1000);
    app.add_option("--calib", a.calib, "the poses are camera poses of this KITTI calib.txt");
    app.add_option("--first", a.first, "first scan of each session");
    app.add_option("--count", a.count, "scans of each session (0: all)");
    app.add_option("--every", a.every,
                   "the PLY files hold the points of every Nth scan (score with ltm_eval dynamic "
                   "--every N)")
        ->check(common::cli::at_least(1));
    app.add_option("--preset", a.preset,
                   "default; short is the same (kept for old command lines: the thresholds follow "
                   "each session's span and views)")
        ->check(common::cli::one_of({"default", "short"}));
    app.add_option("--map", a.map,
                   "a saved maintained map (long_term_map.bin) to start from: the sessions "
                   "continue it");
    app.add_option("--pass-every", a.pass_every,
                   "[s] of scan time: a maintenance pass this often during a session, as the "
                   "component's maintain_every_s (default 0: one pass at the session's end)")
        ->check(common::cli::at_least(0.0));
    app.add_option("--set", a.set, "KEY=VALUE overriding a maintenance key (repeatable)");
    app.add_option("--out", a.out, "output folder")->required();
    app.add_flag("--save", a.save,
                 "save the maintained map after every session as OUT/long_term_map.bin and print "
                 "its size");
    app.add_option("--inspect", a.inspect,
                   "X Y Z: before each session's maintenance, print the histories and verdicts of "
                   "the voxels within 0.4 m (why was it kept or removed?)")
        ->expected(3);
    if (const int rc = common::cli::parse(app, argc, argv); rc >= 0) return rc;
    try {
        return run(a);
    } catch (const common::cli::UsageError& e) {
        return common::cli::usage_error(app, e);
    } catch (const std::exception& e) {
        std::cerr << "ltm_bench_maintenance: " << e.what() << "\n";
        return 1;
    }
}
