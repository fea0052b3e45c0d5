// ltm_bench_odometry: runs the odometry core over a folder of scans and reports speed, peak memory
// and, with a reference trajectory, accuracy (ATE after SE(3) alignment, frame-to-frame relative
// errors, KITTI metric). Options: `ltm_bench_odometry --help`.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <numeric>
#include <string>

#include "common/cli/cli.hpp"
#include "common/core/io_error.hpp"
#include "common/core/kitti_io.hpp"
#include "common/core/process_memory.hpp"
#include "common/core/progress.hpp"
#include "common/core/trajectory_io.hpp"
#include "evaluation/core/ate.hpp"
#include "evaluation/core/kitti_metric.hpp"
#include "evaluation/core/rpe.hpp"
#include "odometry/bench/prior_files.hpp"
#include "odometry/core/odometry.hpp"
#include "odometry/params/odometry_params.hpp"
#include "self_check.hpp"
#include "sources/core/scan_folder.hpp"

namespace {

using namespace ltm;
using Clock = std::chrono::steady_clock;

struct Args {
    std::string dir, out, reference, calib, preset, config, frame_log;
    std::string prior = "none";  // the robot's motion sensors beside the scans (prior_files.hpp)
    int threads = 1;
    std::size_t max_frames = 0;
    std::size_t every = 1;
};

// Declares the command line on `app`, filling `a`.
void add_options(CLI::App& app, Args& a) {
    common::cli::configure(app);
    app.footer(
        "DIR: KITTI layout (velodyne/*.bin) or a PCD/PLY folder (Scans/*.pcd).\n"
        "--reference: KITTI-format poses, one line a frame (the first N lines are used); with\n"
        "--calib (KITTI calib.txt) they are camera poses, converted to the LiDAR.");
    app.add_option("DIR", a.dir, "the scans")->required();
    app.add_option("--threads", a.threads, "worker threads")->check(common::cli::at_least(1));
    app.add_option("--out", a.out, "write the LiDAR poses here (KITTI format)");
    CLI::Option* reference =
        app.add_option("--reference", a.reference, "reference poses: report accuracy");
    app.add_option("--calib", a.calib, "the reference is in the camera frame of this calib.txt")
        ->needs(reference);
    app.add_option("--preset", a.preset, "sensor preset: hdl64, vlp32, vlp16, narrow or os1-64")
        ->default_str("hdl64")
        ->check(CLI::IsMember(common::sensor_preset_names()));
    app.add_option("--config", a.config, "odometry keys overriding the preset (YAML)");
    app.add_option("--max-frames", a.max_frames, "only the first N scans (0: all)");
    app.add_option("--every", a.every,
                   "keep every Nth scan (a hard case: larger motion between scans); the "
                   "reference lines of the kept scans are used")
        ->check(common::cli::at_least(1));
    app.add_option("--frame-log", a.frame_log, "per-frame times and sizes (CSV)");
    app.add_option("--prior", a.prior,
                   "a motion prior from DIR/imu.txt, DIR/wheel_odometry.txt (both: IMU rotation, "
                   "wheel translation) with DIR/extrinsics.txt, as ltm_sim writes them")
        ->check(CLI::IsMember({"none", "imu", "wheel", "both"}))
        ->default_str("none");
}

// Stretches of scans without a registered pose: each lasts from its first scan to the next
// registered one (or the last scan), in sensor time.
struct LostStretches {
    std::size_t lost_scans = 0, count = 0, longest_from = 0;
    double longest = 0.0;
    void add(double stamp, bool registered) {
        if (!registered) {
            ++lost_scans;
            if (!open_) {
                open_ = true;
                from_ = stamp;
                from_index_ = index_;
                ++count;
            }
        } else if (open_) {
            close(stamp);
        }
        last_ = stamp;
        ++index_;
    }
    void finish() {
        if (open_) close(last_);
    }

  private:
    void close(double stamp) {
        open_ = false;
        if (stamp - from_ >= longest) {
            longest = stamp - from_;
            longest_from = from_index_;
        }
    }
    bool open_ = false;
    double from_ = 0.0, last_ = 0.0;
    std::size_t index_ = 0, from_index_ = 0;
};

// CPU time of the calling thread [s] (unlike wall time, not inflated by other processes).
double thread_cpu_seconds() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

odometry::OdometryConfig make_config(const Args& a) {
    const std::string preset = a.preset.empty() ? "hdl64" : a.preset;
    odometry::OdometryConfig config = odometry::preset_config(common::parse_sensor_preset(preset));
    if (!a.config.empty()) config = odometry::load_odometry_config_file(a.config, a.preset);
    config.threads = a.threads;
    common::throw_if(odometry::validate(config), "odometry");
    return config;
}

// The reference lines of the kept scans (empty without --reference).
common::PoseList kept_reference(const Args& a, std::size_t frames) {
    if (a.reference.empty()) return {};
    common::PoseList ref = common::read_kitti_poses(a.reference);
    if (!a.calib.empty())
        ref = common::camera_to_lidar_poses(ref, common::read_kitti_calib_tr(a.calib));
    if (a.every > 1) {
        common::PoseList kept;
        for (std::size_t i = 0; i < ref.size(); i += a.every) kept.push_back(ref[i]);
        ref.swap(kept);
    }
    if (ref.size() < frames) {
        std::printf("warning: reference has %zu poses for %zu frames; comparing the first %zu\n",
                    ref.size(), frames, ref.size());
    }
    ref.resize(std::min(ref.size(), frames));
    return ref;
}

void report_accuracy(const common::PoseList& est, common::PoseList ref) {
    ref.resize(std::min(ref.size(), est.size()));
    const eval::AteResult ate = eval::compute_ate(est, ref);
    std::printf("ATE (SE(3)-aligned, %zu poses): rmse %.4f m  mean %.4f  median %.4f  max %.4f\n",
                ate.n, ate.rmse, ate.mean, ate.median, ate.max);
    const eval::RpeResult rpe = eval::compute_rpe(est, ref, 1);
    std::printf(
        "relative error, consecutive frames (%zu pairs): translation median %.4f m  mean "
        "%.4f  rmse %.4f  max %.4f; rotation median %.4f deg  mean %.4f  max %.4f\n",
        rpe.translation.n, rpe.translation.median, rpe.translation.mean, rpe.translation.rmse,
        rpe.translation.max, rpe.rotation_deg.median, rpe.rotation_deg.mean, rpe.rotation_deg.max);
    const eval::KittiMetric km = eval::compute_kitti_metric(est, ref);
    if (km.segments == 0) {
        std::printf("KITTI metric: run too short (no 10 m segment)\n");
    } else {
        std::printf("KITTI metric (%s lengths, %zu segments): %.3f %%  %.4f deg/100 m\n",
                    km.short_segments ? "short 10..50 m" : "100..800 m", km.segments,
                    km.translation_pct, km.rotation_deg_per_100m);
    }
}

int run(const Args& a) {
    const odometry::OdometryConfig config = make_config(a);
    sources::ScanFolderConfig folder;
    folder.path = a.dir;
    folder.format = sources::ScanFormat::kAuto;
    const sources::ScanFolder data(folder);
    const char* kind = data.format() == sources::ScanFormat::kKittiBin ? "kitti" : "pcd";
    const std::size_t available = (data.size() + a.every - 1) / a.every;
    const std::size_t frames = a.max_frames ? std::min(a.max_frames, available) : available;
    std::printf("%s: %zu %s scans%s%s, %d thread(s), voxel %.2f m\n", a.dir.c_str(), frames, kind,
                a.every > 1 ? (" (every " + std::to_string(a.every) + ")").c_str() : "",
                data.has_times() ? "" : " (no times.txt: 10 Hz assumed)", config.threads,
                config.voxel_size);
    std::vector<odometry::FrameResult> results;  // for the self-check and the frame log

    odometry::Odometry odo(config);
    // The motion prior, fed with its samples up to the end of each scan's sweep.
    odometry::MotionPriorConfig prior_config;
    odometry::bench::PriorSamples prior_samples;
    std::unique_ptr<odometry::MotionPrior> prior;
    std::size_t next_imu = 0, next_wheel = 0;
    if (a.prior != "none") {
        const bool imu = a.prior != "wheel", wheel = a.prior != "imu";
        prior_samples = odometry::bench::read_prior_samples(a.dir, imu, wheel, &prior_config);
        prior = std::make_unique<odometry::MotionPrior>(prior_config);
        odo.set_prior(prior.get());
        std::printf("motion prior: %s (%zu IMU, %zu wheel samples)\n", a.prior.c_str(),
                    prior_samples.imu_stamps.size(), prior_samples.wheel_stamps.size());
    }
    common::PoseList poses;
    std::vector<double> ms;
    std::map<std::string, std::size_t> statuses;
    double pre_ms = 0.0, reg_ms = 0.0, upd_ms = 0.0;
    std::size_t coarse_its = 0, retries = 0;
    std::size_t keyframes = 0, maps_finished = 0, dropped_non_finite = 0, reg_points = 0, its = 0;
    double io_seconds = 0.0, cpu_seconds = 0.0;
    LostStretches stretches;
    common::Progress progress("odometry", frames);
    const auto start = Clock::now();
    for (std::size_t i = 0; i < frames; ++i) {
        const auto t0 = Clock::now();
        const common::PointCloud cloud = data.load(i * a.every);
        const auto t1 = Clock::now();
        if (prior) {
            const float sweep =
                cloud.has_time() ? *std::max_element(cloud.time.begin(), cloud.time.end()) : 0.0f;
            odometry::bench::feed_prior(prior_samples, cloud.stamp + std::max(0.0f, sweep),
                                        &next_imu, &next_wheel, prior.get());
        }
        const double c1 = thread_cpu_seconds();
        const odometry::FrameResult r = odo.register_frame(cloud);
        cpu_seconds += thread_cpu_seconds() - c1;
        const auto t2 = Clock::now();
        maps_finished += odo.take_finished_local_maps().size();  // handed on, dropped here
        io_seconds += std::chrono::duration<double>(t1 - t0).count();
        ms.push_back(std::chrono::duration<double, std::milli>(t2 - t1).count());
        poses.push_back(r.T_odom_lidar);
        ++statuses[odometry::to_string(r.status)];
        // A degenerate scan is not registered, but not lost either (its pose is published).
        if (r.status != odometry::FrameStatus::kDegenerate) {
            stretches.add(r.stamp,
                          r.registered() || r.status == odometry::FrameStatus::kInitialised);
        }
        keyframes += r.keyframe.has_value();
        dropped_non_finite += r.dropped_non_finite;
        reg_points += r.registration_points;
        its += std::size_t(r.iterations);
        retries += r.attempts > 1;
        coarse_its += std::size_t(r.coarse_iterations);
        pre_ms += r.preprocess_ms;
        reg_ms += r.registration_ms;
        upd_ms += r.update_ms;
        if (!r.message.empty()) std::fprintf(stderr, "frame %zu: %s\n", i, r.message.c_str());
        results.push_back(r);
        results.back().keyframe.reset();
        progress.update(i + 1);
    }
    progress.finish();
    const double wall = std::chrono::duration<double>(Clock::now() - start).count();
    const double core = std::accumulate(ms.begin(), ms.end(), 0.0) / 1000.0;
    std::vector<double> sorted = ms;
    std::sort(sorted.begin(), sorted.end());
    const auto pct = [&](double p) {
        return sorted[std::min(sorted.size() - 1, std::size_t(p * sorted.size()))];
    };

    std::printf("frames: %zu;", frames);
    for (const auto& [name, n] : statuses) std::printf(" %s %zu;", name.c_str(), n);
    std::printf(" keyframes %zu; local maps finished %zu, active %zu\n", keyframes, maps_finished,
                odo.active_local_maps().size());
    stretches.finish();
    const std::size_t degenerate = statuses["degenerate"];
    const std::size_t registered = frames - stretches.lost_scans - degenerate;
    std::printf(
        "tracking: %zu of %zu scans registered (%.2f %%), %zu degenerate, %zu not (lost, skipped "
        "or restarted); %zu lost stretches, the longest %.2f s of sensor time (from scan %zu)\n",
        registered, frames, 100.0 * double(registered) / frames, degenerate, stretches.lost_scans,
        stretches.count, stretches.longest, stretches.longest_from);
    std::printf(
        "speed: %.1f frames/s odometry (pre-processing included, file reading excluded), "
        "%.1f frames/s with reading\n",
        frames / core, frames / wall);
    if (config.threads == 1) {
        std::printf("speed by CPU time of the odometry thread: %.1f frames/s (%.2f ms a frame)\n",
                    frames / cpu_seconds, 1000.0 * cpu_seconds / frames);
    }
    std::printf("time a frame: mean %.2f ms  median %.2f  p95 %.2f  max %.2f; reading %.2f ms\n",
                1000.0 * core / frames, pct(0.5), pct(0.95), sorted.back(),
                1000.0 * io_seconds / frames);
    std::printf(
        "stages a frame: pre-processing %.2f ms, registration %.2f ms, map update %.2f ms\n",
        pre_ms / frames, reg_ms / frames, upd_ms / frames);
    std::printf(
        "registration: %.0f points a frame, %.2f iterations a frame (+%.2f coarse), %zu frames "
        "searched beyond the prediction; non-finite points dropped %zu\n",
        double(reg_points) / frames, double(its) / frames, double(coarse_its) / frames, retries,
        dropped_non_finite);
    std::printf("memory: peak resident %.1f MiB (VmHWM); local maps now %.1f MiB\n",
                common::process_memory().peak_mib, odo.memory_bytes() / 1048576.0);
    if (prior && prior->has_imu()) {
        const Eigen::Vector3d b = prior->gyro_bias();
        std::printf("motion prior: gyro bias learnt %.5f %.5f %.5f rad/s (IMU frame)\n", b.x(),
                    b.y(), b.z());
    }
    if (!a.out.empty()) {
        common::write_kitti_poses(a.out, poses);
        std::printf("poses: %s (T_odom_lidar, KITTI format)\n", a.out.c_str());
    }
    const common::PoseList reference = kept_reference(a, poses.size());
    const odometry::bench::SelfCheck check = odometry::bench::self_check(results, reference);
    odometry::bench::print_self_check(check, stdout);
    if (!a.frame_log.empty()) odometry::bench::write_frame_log(a.frame_log, results, ms, check);
    if (!a.reference.empty()) report_accuracy(poses, reference);
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    Args args;
    CLI::App app{
        "Runs the odometry core over a folder of scans: speed, peak memory and, with a "
        "reference, accuracy (ATE, RPE, KITTI metric)",
        "ltm_bench_odometry"};
    add_options(app, args);
    if (const int code = common::cli::parse(app, argc, argv); code >= 0) return code;
    try {
        return run(args);
    } catch (const ltm::common::IoError& e) {
        std::cerr << "ltm_bench_odometry: " << e.what() << "\n";
    } catch (const ltm::common::ConfigError& e) {
        std::cerr << "ltm_bench_odometry: " << e.what() << "\n";
    }
    return 1;
}
