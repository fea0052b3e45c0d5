#include "simulator/cli/sim_run.hpp"

#include <cstdio>
#include <filesystem>
#include <iostream>

#include "common/cli/cli.hpp"
#include "common/core/io_error.hpp"
#include "common/core/kitti_io.hpp"
#include "common/core/ply_io.hpp"
#include "common/core/progress.hpp"
#include "common/core/trajectory_io.hpp"
#include "simulator/cli/pcd_scan.hpp"
#include "simulator/cli/proprio_files.hpp"
#include "simulator/cli/truth_files.hpp"
#include "simulator/core/random.hpp"
#include "simulator/core/scenario_yaml.hpp"
#include "simulator/core/simulator.hpp"

namespace ltm::sim::cli {
namespace {

bool parse_count(const std::string& s, std::size_t& out) {
    if (s.empty() || s.find_first_not_of("0123456789") != std::string::npos) return false;
    out = std::stoull(s);
    return true;
}

// "A:B", "A:" or ":B" with A < B into first, last; false when it is none of them.
bool parse_frames(const std::string& v, std::size_t& first, std::size_t& last) {
    const std::size_t colon = v.find(':');
    if (colon == std::string::npos) return false;
    const std::string lo = v.substr(0, colon), hi = v.substr(colon + 1);
    first = 0;
    last = std::numeric_limits<std::size_t>::max();
    return (lo.empty() || parse_count(lo, first)) && (hi.empty() || parse_count(hi, last)) &&
           first < last;
}

std::string frame_name(std::size_t i, const char* ext) {
    char buf[48];
    std::snprintf(buf, sizeof buf, "%06zu%s", i, ext);
    return buf;
}

// imu.txt, wheel_odometry.txt and extrinsics.txt (proprio_files.hpp) when their rates are set.
void write_motion_sensors(const SimRunOptions& o, const ScenarioConfig& sc, const Simulator& sim,
                          std::size_t first, std::size_t last, const std::string& out) {
    if (o.imu_rate <= 0.0 && o.wheel_rate <= 0.0) return;
    ImuConfig imu_config;
    imu_config.rate = o.imu_rate > 0.0 ? o.imu_rate : 1.0;
    imu_config.T_lidar_imu = default_imu_mount();
    WheelConfig wheel_config;
    wheel_config.rate = o.wheel_rate > 0.0 ? o.wheel_rate : 1.0;
    wheel_config.T_lidar_base.translation() = Eigen::Vector3d(0.0, 0.0, -sc.sensor.height);
    const std::uint64_t seed = hash_mix(sc.seed, std::uint64_t(o.session), 0x1A2Bull);
    ImuSimulator imu(imu_config, seed);
    WheelSimulator wheel(wheel_config, seed);
    std::vector<ImuSample> imu_samples;
    std::vector<WheelSample> wheel_samples;
    simulate_proprioception(sim, first, last, o.imu_rate > 0.0 ? &imu : nullptr,
                            o.wheel_rate > 0.0 ? &wheel : nullptr, &imu_samples, &wheel_samples);
    namespace fs = std::filesystem;
    if (o.imu_rate > 0.0)
        write_imu((fs::path(out) / "imu.txt").string(), imu_samples, imu_config, imu);
    if (o.wheel_rate > 0.0) {
        write_wheel_odometry((fs::path(out) / "wheel_odometry.txt").string(), wheel_samples,
                             wheel_config, wheel);
    }
    write_extrinsics((fs::path(out) / "extrinsics.txt").string(), imu_config, wheel_config);
}

// Every `stride`th point of a scan, with its channels and labels.
void thin(std::size_t stride, SimScan* scan) {
    common::PointCloud& c = scan->cloud;
    std::size_t k = 0;
    for (std::size_t i = 0; i < c.size(); i += stride, ++k) {
        c.points[k] = c.points[i];
        if (c.has_intensity()) c.intensity[k] = c.intensity[i];
        if (c.has_time()) c.time[k] = c.time[i];
        if (i < scan->labels.size()) scan->labels[k] = scan->labels[i];
        if (i < scan->rings.size()) scan->rings[k] = scan->rings[i];
    }
    c.points.resize(k);
    if (c.has_intensity()) c.intensity.resize(k);
    if (c.has_time()) c.time.resize(k);
    scan->labels.resize(std::min(k, scan->labels.size()));
    scan->rings.resize(std::min(k, scan->rings.size()));
}

}  // namespace

void add_seed_option(CLI::App& app, SimRunOptions& o) {
    app.add_option("--seed", o.seed, "random seed (default: the scenario's)")
        ->default_str("")
        ->each([&o](const std::string&) { o.has_seed = true; });
}

void add_frames_option(CLI::App& app, SimRunOptions& o, const std::string& help) {
    app.add_option_function<std::string>(
           "--frames", [&o](const std::string& v) { parse_frames(v, o.first, o.last); }, help)
        ->type_name("A:B")
        ->check(CLI::Validator(
            [](std::string& v) -> std::string {
                std::size_t first = 0, last = 0;
                if (parse_frames(v, first, last)) return "";
                return "expected A:B with A < B (e.g. 0:100, 50:), got '" + v + "'";
            },
            ""));
}

void add_sim_options(CLI::App& app, SimRunOptions& o) {
    common::cli::configure(app);
    app.footer(
        "Writes DIR/velodyne/NNNNNN.bin (--format pcd: DIR/Scans/NNNNNN.pcd with per-point time\n"
        "t [s after the stamp] for raw sweeps), labels/, times.txt, poses.txt (KITTI, LiDAR\n"
        "frame), poses_tum.txt, calib.txt (identity), truth_mesh.ply, scenario.yaml,\n"
        "objects.txt, changes.txt, actors.txt, kidnaps.txt, and the robot's motion sensors:\n"
        "imu.txt (gyro, accelerometer), wheel_odometry.txt and extrinsics.txt (their mounts).");
    app.add_option("SCENARIO", o.scenario, "the scenario (YAML)")->required();
    add_seed_option(app, o);
    app.add_option("--session", o.session, "session of the scenario")
        ->check(common::cli::at_least(0));
    add_frames_option(app, o, "scans A..B-1 (A: or :B allowed), written numbered from 0");
    app.add_option("--sensor", o.sensor,
                   "sensor preset replacing the scenario's: " + sensor_preset_names());
    app.add_option("--format", o.format,
                   "scan files: kitti (velodyne/*.bin: x y z intensity) or pcd (Scans/*.pcd: x y "
                   "z intensity t, t = per-point time of raw sweeps)")
        ->check(common::cli::one_of({"kitti", "pcd"}))
        ->default_str("kitti");
    app.add_flag("--truth-only", o.truth_only,
                 "only times, poses, objects, changes, actors and kidnaps (no scans, labels or "
                 "truth mesh: fast)");
    app.add_option("--point-stride", o.point_stride,
                   "keep every Nth point of each scan (labels follow; default 1: all)")
        ->check(common::cli::at_least(1));
    app.add_option("--imu-rate", o.imu_rate, "IMU samples a second (imu.txt; 0: none)")
        ->check(CLI::Range(0.0, 2000.0))
        ->default_str("200");
    app.add_option("--wheel-rate", o.wheel_rate,
                   "wheel odometry samples a second (wheel_odometry.txt; 0: none)")
        ->check(CLI::Range(0.0, 1000.0))
        ->default_str("50");
    app.add_flag("--quiet", o.quiet, "no summary and no progress");
    app.add_option("--out", o.out, "the output folder")->required();
}

ScenarioConfig load_with_options(const SimRunOptions& o) {
    ScenarioConfig sc = load_scenario(o.scenario);
    if (o.has_seed) sc.seed = o.seed;
    if (!o.sensor.empty() && !replace_sensor(o.sensor, sc.sensor)) {
        throw ScenarioError("--sensor " + o.sensor + ": unknown (known: " + sensor_preset_names() +
                            ")");
    }
    return sc;
}

int run_sim(const SimRunOptions& o) {
    try {
        const ScenarioConfig sc = load_with_options(o);
        const Simulator sim(sc, o.session);
        for (const auto& w : sim.warnings()) std::cerr << "ltm_sim: warning: " << w << "\n";
        const std::size_t first = std::min(o.first, sim.num_scans());
        const std::size_t last = std::min(o.last, sim.num_scans());
        if (first >= last) {
            std::cerr << "ltm_sim: --frames selects no scans (session " << o.session << " has "
                      << sim.num_scans() << ")\n";
            return 2;
        }
        if (!o.quiet) {
            std::cerr << "ltm_sim: " << sc.name << " session " << o.session << " ("
                      << sc.sessions[static_cast<std::size_t>(o.session)].name << "), sensor "
                      << sc.sensor.model << ", seed " << sc.seed << ": scans " << first << ".."
                      << last - 1 << " of " << sim.num_scans() << "; " << sim.objects().size()
                      << " objects, " << sim.world().static_mesh().num_triangles() << " triangles, "
                      << sim.actors().size() << " moving actors, " << sim.plan().changed_ids.size()
                      << " objects changed between sessions\n";
        }
        namespace fs = std::filesystem;
        const fs::path out(o.out);
        const bool pcd = o.format == "pcd";
        const fs::path scans = out / (pcd ? "Scans" : "velodyne");
        std::error_code ec;
        if (o.truth_only) {
            fs::create_directories(out, ec);
        } else {
            fs::create_directories(scans, ec);
            fs::create_directories(out / "labels", ec);
        }
        if (ec || !fs::is_directory(o.truth_only ? out : scans))
            throw common::IoError(o.out, "cannot create the output folder");

        common::Progress progress("ltm_sim", last - first, "scans");
        std::vector<double> times;
        common::PoseList poses;
        common::Trajectory tum;
        std::vector<std::size_t> kidnap_frames;
        std::vector<double> kidnap_stamps;
        SimScan scan;
        for (std::size_t i = first; i < last; ++i) {
            const std::size_t k = i - first;
            if (o.truth_only) {
                times.push_back(sim.stamp(i));
                poses.push_back(sim.pose(i));
                common::StampedPose sp;
                sp.stamp = sim.stamp(i);
                sp.pose = sim.pose(i);
                tum.push_back(sp);
                if (sim.after_kidnap(i)) {
                    kidnap_frames.push_back(k);
                    kidnap_stamps.push_back(sim.stamp(i));
                }
                if (!o.quiet) progress.update(k + 1);
                continue;
            }
            sim.scan(i, scan);
            if (o.point_stride > 1) thin(o.point_stride, &scan);
            if (pcd) {
                write_scan_pcd((scans / frame_name(k, ".pcd")).string(), scan.cloud);
            } else {
                common::write_kitti_bin((scans / frame_name(k, ".bin")).string(), scan.cloud);
            }
            write_labels((out / "labels" / frame_name(k, ".label")).string(), scan.labels);
            times.push_back(scan.cloud.stamp);
            poses.push_back(scan.T_world_lidar);
            common::StampedPose sp;
            sp.stamp = scan.cloud.stamp;
            sp.pose = scan.T_world_lidar;
            tum.push_back(sp);
            if (scan.after_kidnap) {
                kidnap_frames.push_back(k);
                kidnap_stamps.push_back(scan.cloud.stamp);
            }
            if (!o.quiet) progress.update(k + 1);
        }
        if (!o.quiet) progress.finish();
        common::write_times((out / "times.txt").string(), times);
        common::write_kitti_poses((out / "poses.txt").string(), poses);
        common::write_tum_trajectory((out / "poses_tum.txt").string(), tum);
        write_identity_calib((out / "calib.txt").string());
        if (!o.truth_only) common::write_ply((out / "truth_mesh.ply").string(), sim.truth_mesh());
        write_objects((out / "objects.txt").string(), sim);
        write_changes((out / "changes.txt").string(), sim);
        write_actors((out / "actors.txt").string(), sim);
        write_kidnaps((out / "kidnaps.txt").string(), kidnap_frames, kidnap_stamps);
        write_motion_sensors(o, sc, sim, first, last, out.string());
        copy_scenario(o.scenario, (out / "scenario.yaml").string(),
                      "seed " + std::to_string(sc.seed) + ", session " + std::to_string(o.session) +
                          ", frames " + std::to_string(first) + ":" + std::to_string(last) +
                          ", sensor " + sc.sensor.model + ", format " + o.format);
        return 0;
    } catch (const ScenarioError& e) {
        std::cerr << "ltm_sim: " << e.what() << "\n";
    } catch (const common::IoError& e) {
        std::cerr << "ltm_sim: " << e.what() << "\n";
    }
    return 1;
}

int sim_main(int argc, char** argv) {
    SimRunOptions o;
    CLI::App app{"Writes one session of a simulated scenario as a KITTI-layout folder", "ltm_sim"};
    add_sim_options(app, o);
    if (const int code = common::cli::parse(app, argc, argv); code >= 0) return code;
    return run_sim(o);
}

}  // namespace ltm::sim::cli
