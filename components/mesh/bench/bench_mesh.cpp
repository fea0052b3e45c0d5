// ltm_bench_mesh: the dense mesh from scans at given poses (issue 14). The scans build the
// odometry's local maps at their poses (Odometry::place_frame: no registration), each finished
// local map becomes a mesh chunk (signed distance of its voxels, marching cubes), the chunks join
// in a MeshAtlas and the global mesh is written as PLY. Prints the time a scan (voxel map and
// mesh apart), meshing time, vertices and faces, and the time to follow an optimisation of the
// graph (every anchor moved) without re-integration. Optionally writes the points of the scans
// left out (--every) and the points integrated, for scoring with `ltm_eval mesh`.
//
//   ltm_bench_mesh --map MAP_DIR [--set KEY=VALUE ...] --out mesh.ply
//   ltm_bench_mesh DIR --poses POSES.txt [--calib CALIB] [--preset P] [--voxel V]
//                  [--frames A:B] [--every K] [--offset O] [--set KEY=VALUE ...]
//                  [--heldout-out FILE.ply] [--observed-out FILE.ply] --out mesh.ply
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <string>
#include <unordered_set>
#include <vector>

#include "common/cli/cli.hpp"
#include "common/cli/config_set.hpp"
#include "common/core/io_error.hpp"
#include "common/core/kitti_io.hpp"
#include "common/core/ply_io.hpp"
#include "common/core/process_memory.hpp"
#include "common/core/progress.hpp"
#include "common/core/trajectory_io.hpp"
#include "map/core/map_store.hpp"
#include "mesh/core/mesh_atlas.hpp"
#include "mesh/core/mesh_chunk.hpp"
#include "mesh/core/triangle_mesh.hpp"
#include "odometry/core/map_handover.hpp"
#include "odometry/core/odometry.hpp"
#include "sources/core/scan_folder.hpp"

namespace {

using namespace ltm;
using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

struct Args {
    std::string dir, poses, calib, out, heldout_out, observed_out, union_out, frames, map;
    std::string preset = "hdl64";
    double voxel = 0.0, observed_range = 0.0;
    std::size_t every = 1, offset = 0;
    std::vector<std::string> set, odometry_set;
};

double percentile(std::vector<double> v, double q) {
    if (v.empty()) return 0.0;
    const std::size_t k = std::min(v.size() - 1, std::size_t(q * double(v.size() - 1) + 0.5));
    std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(k), v.end());
    return v[k];
}

// Points thinned to one a cell of `cell` metres (the first in each cell).
class ThinnedCloud {
  public:
    explicit ThinnedCloud(double cell) : cell_(cell) {}
    void add(const Eigen::Vector3f& p) {
        if (cells_.insert(mesh::cell_key(p.cast<double>(), cell_)).second)
            cloud_.points.push_back(p);
    }
    const common::PlyCloud& cloud() const { return cloud_; }

  private:
    double cell_;
    std::unordered_set<std::uint64_t> cells_;
    common::PlyCloud cloud_;
};

std::pair<std::size_t, std::size_t> frame_range(const std::string& frames, std::size_t n) {
    if (frames.empty()) return {0, n};
    const std::size_t colon = frames.find(':');
    if (colon == std::string::npos)
        throw common::cli::UsageError("--frames", "expected A:B (A: or :B allowed)");
    try {
        const std::size_t a = colon == 0 ? 0 : std::stoul(frames.substr(0, colon));
        const std::size_t b = colon + 1 == frames.size() ? n : std::stoul(frames.substr(colon + 1));
        if (a >= b || b > n)
            throw common::cli::UsageError(
                "--frames", frames + " is not a range of the " + std::to_string(n) + " scans");
        return {a, b};
    } catch (const std::logic_error&) {
        throw common::cli::UsageError("--frames", "expected A:B with numbers, got " + frames);
    }
}

// The mesh of a saved map: every local map a chunk at its optimised anchor (what the mesh
// component does with the map it is given, and the time to mesh a whole site).
int run_map(const Args& a, const mesh::MeshConfig& mc) {
    auto t0 = Clock::now();
    const map::LoadedMap loaded = map::load_map(a.map);
    const double load_ms = ms_since(t0);
    for (const std::string& r : loaded.refused) std::fprintf(stderr, "refused: %s\n", r.c_str());
    std::map<std::uint64_t, Eigen::Isometry3d> graph;
    for (const map::PoseGraphNode& n : loaded.map.nodes) graph[n.id] = n.T_world_anchor;
    mesh::MeshAtlas atlas(mc);
    t0 = Clock::now();
    for (const map::StoredLocalMap& m : loaded.map.local_maps) {
        common::LocalMapData data = *m.data;
        data.id = m.node;  // local map ids repeat across sessions; graph nodes do not
        atlas.add(mesh::prepare_chunk(data, mc));
    }
    const double prepare_ms = ms_since(t0);
    atlas.set_graph(graph);
    t0 = Clock::now();
    atlas.update();  // each local map meshes the places it owns
    const double update_ms = ms_since(t0);
    t0 = Clock::now();
    const common::PlyMesh global = atlas.global_mesh();
    const double assemble_ms = ms_since(t0);
    common::write_ply(a.out, global);
    const mesh::AtlasTotals tot = atlas.totals();
    std::printf("ltm_bench_mesh: map %s (%zu local maps, %zu graph nodes; loaded in %.0f ms)\n",
                a.map.c_str(), loaded.map.local_maps.size(), graph.size(), load_ms);
    std::printf(
        "  meshing: %.0f ms = voxels and cells %.0f ms + ownership and meshing %.0f ms (signed "
        "distance %.0f ms, marching cubes %.0f ms, %zu local maps meshed) + global mesh %.0f ms\n",
        prepare_ms + update_ms + assemble_ms, prepare_ms, update_ms, tot.fill_ms, tot.mesh_ms,
        tot.meshings, assemble_ms);
    std::printf("  mesh: %zu vertices, %zu faces (%zu in the chunks), area %.0f m^2\n",
                global.vertices.size(), global.triangles.size(), tot.triangles,
                mesh::surface_area(global));
    // The map's own loop closures: its anchors where the odometry put them, then optimised again
    // (what the mesh goes through when the graph is optimised; nothing re-integrated).
    std::map<std::uint64_t, Eigen::Isometry3d> odometry_graph;
    double moved = 0.0;
    for (const map::PoseGraphNode& n : loaded.map.nodes) {
        odometry_graph[n.id] = n.T_odom_anchor;
        moved = std::max(moved,
                         (n.T_odom_anchor.translation() - n.T_world_anchor.translation()).norm());
    }
    atlas.set_graph(odometry_graph);
    atlas.update();
    const mesh::AtlasTotals before = atlas.totals();
    atlas.set_graph(graph);
    t0 = Clock::now();
    const std::size_t changed = atlas.update().size();
    const double reupdate_ms = ms_since(t0);
    t0 = Clock::now();
    const std::size_t faces = atlas.global_mesh().triangles.size();
    const double reassemble_ms = ms_since(t0);
    const mesh::AtlasTotals after = atlas.totals();
    std::printf(
        "  the map's optimisation (anchors moved up to %.2f m from the odometry's): %zu chunks "
        "changed, update %.0f ms (of which %zu local maps meshed again from their voxels: %.0f "
        "ms) + global mesh %.0f ms; %zu faces\n",
        moved, changed, reupdate_ms, after.meshings - before.meshings,
        after.fill_ms + after.mesh_ms - before.fill_ms - before.mesh_ms, reassemble_ms, faces);
    std::printf("  peak memory %.0f MiB\n  wrote %s\n", common::process_memory().peak_mib,
                a.out.c_str());
    return 0;
}

int run(const Args& a) {
    odometry::OdometryConfig oc = odometry::preset_config(common::parse_sensor_preset(a.preset));
    if (a.voxel > 0.0) oc.voxel_size = a.voxel;
    common::cli::apply_config_sets(oc, a.odometry_set, "OdometryConfig", "voxel.min_planarity");
    mesh::MeshConfig mc;
    common::cli::apply_config_sets(mc, a.set, "MeshConfig", "grid_size");
    common::throw_if(mesh::validate(mc), "mesh");
    if (!a.map.empty()) {
        if (!a.dir.empty() || !a.poses.empty())
            throw common::cli::UsageError("--map", "give a map or scans with --poses, not both");
        return run_map(a, mc);
    }
    if (a.dir.empty() || a.poses.empty())
        throw common::cli::UsageError("give DIR --poses POSES.txt (scans) or --map MAP_DIR");

    sources::ScanFolderConfig fc;
    fc.path = a.dir;
    const sources::ScanFolder folder(fc);
    common::PoseList poses = common::read_kitti_poses(a.poses);
    if (!a.calib.empty())
        poses = common::camera_to_lidar_poses(poses, common::read_kitti_calib_tr(a.calib));
    if (poses.size() < folder.size())
        throw common::IoError(a.poses, std::to_string(poses.size()) + " poses for " +
                                           std::to_string(folder.size()) + " scans");
    const auto [first, last] = frame_range(a.frames, folder.size());

    odometry::Odometry odometry(oc);
    odometry::HandoverConfig hc;
    hc.snapshot_every_keyframes = 0;  // finished maps only: what the mesh component meshes
    odometry::MapHandover handover(hc);
    mesh::MeshAtlas atlas(mc);
    std::vector<double> place_ms, chunk_ms;
    std::size_t voxels_used = 0, voxels_left = 0;
    std::size_t integrated = 0, heldout = 0;
    ThinnedCloud observed(0.05);
    common::PlyCloud heldout_points;
    const double max_range = oc.preprocess.max_range;
    const double observed_range = a.observed_range > 0.0 ? a.observed_range : max_range;

    // As the mesh component does: each finished local map joins the atlas at its anchor (here
    // the given poses: the graph is the truth) and meshes the places it owns.
    std::map<std::uint64_t, Eigen::Isometry3d> graph;
    auto mesh_maps = [&](const std::vector<common::LocalMapData>& maps) {
        for (const common::LocalMapData& m : maps) {
            if (!m.finished) continue;
            const auto t0 = Clock::now();
            mesh::MeshChunk c = mesh::prepare_chunk(m, mc);
            voxels_used += c.voxels.size();
            voxels_left += c.voxels_left;
            graph[m.id] = m.T_odom_anchor;
            atlas.add(std::move(c));
            atlas.set_graph(graph);
            atlas.update();
            chunk_ms.push_back(ms_since(t0));
        }
    };

    common::Progress progress("mesh", last - first, "scans");
    for (std::size_t i = first; i < last; ++i) {
        const bool use = (i - first) % a.every == a.offset % a.every;
        const common::PointCloud cloud = folder.load(i);
        const Eigen::Isometry3f T = poses[i].cast<float>();
        if (!use) {
            for (const Eigen::Vector3f& p : cloud.points)
                if (p.allFinite() && p.norm() <= max_range && p.norm() > 1e-3f)
                    heldout_points.points.push_back(T * p);
            ++heldout;
        } else {
            const auto t0 = Clock::now();
            const odometry::FrameResult r = odometry.place_frame(cloud, poses[i]);
            place_ms.push_back(ms_since(t0));
            mesh_maps(handover.after_frame(odometry, r, i).local_maps);
            ++integrated;
            if (!a.observed_out.empty())
                for (const Eigen::Vector3f& p : cloud.points)
                    if (p.allFinite() && p.norm() <= observed_range) observed.add(T * p);
        }
        progress.update(i - first + 1);
    }
    mesh_maps(handover.finish(odometry));
    progress.finish();

    const double fill_ms = atlas.totals().fill_ms, cube_ms = atlas.totals().mesh_ms;
    auto t0 = Clock::now();
    const common::PlyMesh global = atlas.global_mesh();
    const double assemble_ms = ms_since(t0);
    common::write_ply(a.out, global);
    if (!a.union_out.empty()) {  // every chunk whole: the overlaps twice (for comparison)
        common::PlyMesh all;
        for (const std::uint64_t id : atlas.ids())
            mesh::append(all, atlas.chunk(id)->mesh, atlas.T_world_anchor(id));
        common::write_ply(a.union_out, all);
    }

    // An optimisation moves every anchor (a drift correction growing to 0.5 m and 0.5 deg along
    // the run): the chunks follow, nothing is re-integrated.
    std::map<std::uint64_t, Eigen::Isometry3d> moved;
    std::size_t k = 0;
    for (const auto& [id, T] : graph) {
        const double f = double(++k) / double(graph.size());
        Eigen::Isometry3d D = Eigen::Isometry3d::Identity();
        D.linear() =
            Eigen::AngleAxisd(f * 0.5 * M_PI / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
        D.translation() = Eigen::Vector3d(0.5 * f, -0.3 * f, 0.1 * f);
        moved[id] = D * T;
    }
    const mesh::AtlasTotals before_move = atlas.totals();
    atlas.set_graph(moved);
    t0 = Clock::now();
    const std::size_t changed = atlas.update().size();
    const double reown_ms = ms_since(t0);
    t0 = Clock::now();
    const common::PlyMesh after = atlas.global_mesh();
    const double reassemble_ms = ms_since(t0);

    double chunk_area = 0.0;
    for (const std::uint64_t id : atlas.ids())
        chunk_area += mesh::surface_area(atlas.chunk(id)->mesh);
    const double area = mesh::surface_area(global);
    const mesh::AtlasTotals tot = atlas.totals();
    const std::size_t remeshed = tot.meshings - before_move.meshings;
    const double remesh_ms = tot.fill_ms + tot.mesh_ms - before_move.fill_ms - before_move.mesh_ms;
    const double place_sum = [&] {
        double s = 0.0;
        for (const double x : place_ms) s += x;
        return s;
    }();
    const double per_scan_mesh = (fill_ms + cube_ms) / double(std::max<std::size_t>(1, integrated));
    std::printf("ltm_bench_mesh: %s, scans %zu..%zu, %zu integrated, %zu held out\n", a.dir.c_str(),
                first, last, integrated, heldout);
    std::printf(
        "  local maps: voxel %.2f m, %zu chunks, %zu voxels meshed, %zu left out (no plane or "
        "too few points); mesh grid %.3f m, truncation %.3f m\n",
        oc.voxel_size, tot.chunks, voxels_used, voxels_left,
        mesh::effective_grid_size(mc, oc.voxel_size),
        mesh::effective_truncation(mc, oc.voxel_size));
    std::printf(
        "  time a scan: voxel map %.2f ms (median %.2f, p90 %.2f) + signed distance and "
        "marching cubes %.2f ms = %.2f ms\n",
        place_sum / double(std::max<std::size_t>(1, integrated)), percentile(place_ms, 0.5),
        percentile(place_ms, 0.9), per_scan_mesh,
        (place_sum + fill_ms + cube_ms) / double(std::max<std::size_t>(1, integrated)));
    std::printf(
        "  meshing: %.0f ms in all (signed distance %.0f ms, marching cubes %.0f ms; a local "
        "map joining the atlas: median %.0f ms, max %.0f ms), global mesh %.0f ms\n",
        fill_ms + cube_ms, fill_ms, cube_ms, percentile(chunk_ms, 0.5),
        chunk_ms.empty() ? 0.0 : *std::max_element(chunk_ms.begin(), chunk_ms.end()), assemble_ms);
    std::printf(
        "  mesh: %zu vertices, %zu faces (%zu in the chunks), area %.0f m^2 (chunks %.0f m^2: "
        "%.2fx where local maps overlap)\n",
        global.vertices.size(), global.triangles.size(), tot.triangles, area, chunk_area,
        chunk_area / std::max(area, 1e-9));
    std::printf(
        "  after an optimisation moving every anchor: %zu chunks moved, update %.0f ms (of which "
        "%zu local maps meshed again from their voxels: %.0f ms) + global mesh %.0f ms; "
        "re-integrating the scans is never needed; %zu faces\n",
        changed, reown_ms, remeshed, remesh_ms, reassemble_ms, after.triangles.size());
    std::printf("  peak memory %.0f MiB\n  wrote %s\n", common::process_memory().peak_mib,
                a.out.c_str());
    if (!a.heldout_out.empty()) {
        common::write_ply(a.heldout_out, heldout_points);
        std::printf("  wrote %s (%zu points of the scans left out)\n", a.heldout_out.c_str(),
                    heldout_points.points.size());
    }
    if (!a.observed_out.empty()) {
        common::write_ply(a.observed_out, observed.cloud());
        std::printf("  wrote %s (%zu points integrated, one per 5 cm cell)\n",
                    a.observed_out.c_str(), observed.cloud().points.size());
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"The dense mesh from scans at given poses: time, size, PLY", "ltm_bench_mesh"};
    Args a;
    common::cli::configure(app);
    app.add_option("DIR", a.dir, "scan folder (KITTI layout)");
    app.add_option("--poses", a.poses, "KITTI-format poses, one line a scan");
    app.add_option("--map", a.map,
                   "instead of scans: a saved map directory, meshed at its optimised anchors");
    app.add_option("--calib", a.calib, "the poses are camera poses of this KITTI calib.txt");
    app.add_option("--preset", a.preset, "sensor preset of the odometry's local maps")
        ->check(common::cli::one_of(common::sensor_preset_names()));
    app.add_option("--voxel", a.voxel, "local-map voxel size [m] (default: the preset's)")
        ->check(common::cli::at_least(0.01));
    app.add_option("--frames", a.frames, "scans A..B-1 (A: or :B allowed)");
    app.add_option("--every", a.every, "integrate every Kth scan of the range")
        ->check(common::cli::at_least(1));
    app.add_option("--offset", a.offset, "... starting at this one (the others are held out)");
    app.add_option("--set", a.set,
                   "KEY=VALUE overriding a mesh key (repeatable), e.g. grid_size=0.1");
    app.add_option("--odometry-set", a.odometry_set,
                   "KEY=VALUE overriding a key of the odometry's local maps (repeatable)");
    app.add_option("--heldout-out", a.heldout_out,
                   "write the points of the scans left out (world frame, PLY)");
    app.add_option("--observed-out", a.observed_out,
                   "write the points integrated (world frame, one per 5 cm, PLY)");
    app.add_option("--observed-range", a.observed_range,
                   "[m] --observed-out keeps points this near the sensor (default: the preset's "
                   "max range)");
    app.add_option("--union-out", a.union_out,
                   "also write every chunk whole, without ownership (overlaps twice), as PLY");
    app.add_option("--out", a.out, "the global mesh (PLY)")->required();
    if (const int rc = common::cli::parse(app, argc, argv); rc >= 0) return rc;
    try {
        return run(a);
    } catch (const common::cli::UsageError& e) {
        return common::cli::usage_error(app, e);
    } catch (const std::exception& e) {
        std::cerr << "ltm_bench_mesh: " << e.what() << "\n";
        return 1;
    }
}
