// ltm_bench_localise: localisation of a scan folder on a saved map.
//   --mode global: every scan on its own against the whole map (no prior, no odometry); one line
//                  a scan, `frame time_s ok [12 pose numbers]` (what `ltm_eval reloc` reads).
//   --mode track:  the scans in sequence through odometry, tracking and automatic
//                  re-localisation; the same line a scan (ok: a valid pose in the map).
// With --reference (KITTI poses of the scans; --reference-transform maps them into the map's
// frame) it prints the success rate, confident wrong answers and time, and in track mode the
// tracking ATE and how long each start and jump (kidnap) took to be re-localised.
#include <malloc.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>
#include <string>
#include <unordered_map>
#include <vector>

#include "common/cli/cli.hpp"
#include "common/core/config_check.hpp"
#include "common/core/io_error.hpp"
#include "common/core/progress.hpp"
#include "common/core/sensor_preset.hpp"
#include "common/core/trajectory_io.hpp"
#include "localisation/component/localiser_params.hpp"
#include "localisation/core/localiser.hpp"
#include "localisation/core/map_pages.hpp"
#include "localisation/core/neighbourhood_builder.hpp"
#include "map/core/map_store.hpp"
#include "odometry/core/odometry.hpp"
#include "odometry/params/odometry_params.hpp"
#include "registration/core/preprocess.hpp"
#include "runtime/parameters.hpp"
#include "sources/core/scan_folder.hpp"

namespace {

using namespace ltm;
using Clock = std::chrono::steady_clock;
constexpr double kDegToRad = M_PI / 180.0;

struct Args {
    std::string map, dir, reference, reference_transform, preset = "hdl64", mode = "global", out;
    std::string config, trajectory;
    std::size_t every = 1, max_frames = 0, first = 0;
    std::vector<std::size_t> only;  // global mode: localise these frames alone (same perturbations)
    double perturb_yaw = 0.0, perturb_shift = 0.0;
    unsigned seed = 1;
    double max_translation = 0.5, max_rotation = 2.0;
    double near = 10.0;
    double revisit = 5.0, exclude_seconds = 60.0;
    bool no_features = false, verify_reference = false;
    // Track mode: tracking on the paged map's neighbourhood (map_pages.hpp; 0: the whole map).
    double neighbourhood_radius = 0.0, rebuild_distance = 40.0;
    bool settle = false;  // wait for each neighbourhood build (reproducible runs)
    // Track mode: the first scan's global localisation narrowed to this map keyframe's place.
    int hint_keyframe = -1;
    double hint_radius = 10.0;
};

// CPU time of the whole process [s]: on a shared, loaded machine the wall time of a scan is
// mostly waiting; this is what one core spends on it.
double cpu_seconds() {
    timespec ts{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

double percentile(std::vector<double> v, double q) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    return v[std::min(v.size() - 1, std::size_t(q * double(v.size() - 1) + 0.5))];
}

std::pair<double, double> error_of(const Eigen::Isometry3d& est, const Eigen::Isometry3d& ref) {
    const Eigen::Isometry3d d = ref.inverse() * est;
    return {d.translation().norm(), Eigen::AngleAxisd(d.linear()).angle() / kDegToRad};
}

Eigen::Isometry3d read_transform(const std::string& path) {
    const common::PoseList p = common::read_kitti_poses(path);
    if (p.size() != 1) throw common::IoError(path, "expected one KITTI 3x4 line (T_map_reference)");
    return p[0];
}

void write_line(std::ostream& os, std::size_t frame, double time_s, bool ok,
                const Eigen::Isometry3d& T) {
    os << frame << ' ' << time_s << ' ' << (ok ? 1 : 0);
    if (ok) {
        const Eigen::Matrix<double, 3, 4> m = T.matrix().topRows<3>();
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 4; ++c) os << ' ' << m(r, c);
    }
    os << '\n';
}

// --mode recall: place recognition on the map's own keyframes, ScanContext++ (the localisation
// descriptor) beside plain Scan Context (the loop descriptor). Every keyframe with a keyframe of
// another time (more than --exclude-seconds apart) within --revisit metres is a revisit query;
// recall@1: the best candidate of the ring-key top-25 (full descriptor distance) is within
// --revisit metres of it. Opposite-direction revisits count like the others.
int run_recall(const Args& a) {
    const map::LoadedMap loaded = map::load_map(a.map);
    const map::MapData& m = loaded.map;
    if (!map::has_localisation_descriptors(m.localisation_descriptor_config))
        throw common::IoError(a.map, "has no ScanContext++ descriptors (format 1)");
    std::unordered_map<std::uint64_t, Eigen::Isometry3d> anchors;
    for (const map::PoseGraphNode& n : m.nodes) anchors[n.id] = n.T_world_anchor;
    struct Kf {
        Eigen::Vector3d p;
        Eigen::Vector3d heading;
        double stamp;
        const map::StoredKeyframe* k;
    };
    std::vector<Kf> kfs;
    for (const auto& k : m.keyframes) {
        const auto it = anchors.find(k->node);
        if (it == anchors.end() || k->localisation_descriptor.empty()) continue;
        const Eigen::Isometry3d T = it->second * k->data.T_anchor_lidar;
        kfs.push_back({T.translation(), T.linear().col(0), k->data.stamp, k.get()});
    }
    struct Kind {
        const char* name;
        bool plus;
        places::ScanContextConfig config;
        places::RingKeyIndex index;
        std::size_t queries = 0, hits = 0, opposite = 0, opposite_hits = 0;
    };
    Kind kinds[2] = {
        {"Scan Context (max height, cosine)", false, m.descriptor_config,
         places::RingKeyIndex(m.descriptor_config.rings)},
        {"ScanContext++ (mean/std, 2-Wasserstein)", true, m.localisation_descriptor_config,
         places::RingKeyIndex(m.localisation_descriptor_config.rings)}};
    for (Kind& kind : kinds) {
        for (std::size_t j = 0; j < kfs.size(); ++j) {
            const places::ScanContext& d =
                kind.plus ? kfs[j].k->localisation_descriptor : kfs[j].k->descriptor;
            kind.index.add(places::ring_key(d), std::uint32_t(j));
        }
    }
    for (std::size_t i = 0; i < kfs.size(); ++i) {
        bool revisit = false, opposite = false;
        for (const Kf& o : kfs) {
            if (std::abs(o.stamp - kfs[i].stamp) <= a.exclude_seconds) continue;
            if ((o.p - kfs[i].p).head<2>().norm() > a.revisit) continue;
            revisit = true;
            opposite = opposite || o.heading.dot(kfs[i].heading) < -0.5;
        }
        if (!revisit) continue;
        for (Kind& kind : kinds) {
            const places::ScanContext& q =
                kind.plus ? kfs[i].k->localisation_descriptor : kfs[i].k->descriptor;
            double best = 1e300;
            std::size_t best_j = kfs.size();
            for (const places::RingKeyNeighbour& n : kind.index.nearest(places::ring_key(q), 60)) {
                if (std::abs(kfs[n.item].stamp - kfs[i].stamp) <= a.exclude_seconds) continue;
                const places::ScanContext& c =
                    kind.plus ? kfs[n.item].k->localisation_descriptor : kfs[n.item].k->descriptor;
                const places::ScanContextMatch match = places::compare(q, c, kind.config);
                if (match.valid && match.distance < best) {
                    best = match.distance;
                    best_j = n.item;
                }
            }
            const bool hit =
                best_j < kfs.size() && (kfs[best_j].p - kfs[i].p).head<2>().norm() <= a.revisit;
            ++kind.queries;
            kind.hits += hit;
            kind.opposite += opposite;
            kind.opposite_hits += opposite && hit;
        }
    }
    std::printf(
        "%s: %zu keyframes; revisit queries: a keyframe of another time (> %.0f s apart) "
        "within %.1f m\n",
        a.map.c_str(), kfs.size(), a.exclude_seconds, a.revisit);
    for (const Kind& kind : kinds) {
        std::printf(
            "%-40s recall@1 %zu/%zu (%.1f %%); with an opposite-direction revisit "
            "%zu/%zu\n",
            kind.name, kind.hits, kind.queries,
            kind.queries ? 100.0 * double(kind.hits) / double(kind.queries) : 0.0,
            kind.opposite_hits, kind.opposite);
    }
    return 0;
}

int run(const Args& a) {
    if (a.mode == "recall") return run_recall(a);
    const common::SensorPreset preset = common::parse_sensor_preset(a.preset);
    localisation::LocaliserConfig lc = localisation::localiser_preset(preset);
    if (!a.config.empty()) {
        runtime::Parameters params = runtime::Parameters::from_file(a.config, "localisation");
        lc = localisation::load_localiser_config(params, preset);
        params.check_all_used();
    }
    if (a.no_features) lc.global.local_features = false;
    localisation::LocalisationMapConfig mc = localisation::localisation_map_preset(preset);
    mc.local_features = !a.no_features;
    const auto t_load = Clock::now();
    std::vector<std::string> refused;
    const auto map =
        localisation::load_localisation_map(a.map, mc, &refused, a.neighbourhood_radius);
    for (const std::string& r : refused) std::fprintf(stderr, "map: refused %s\n", r.c_str());
    std::printf(
        "map %s: %zu keyframes, %zu local maps, %zu voxels,  %zu session(s), path %.0f m, %zu "
        "local features%s, "
        "loaded in %.2f s\n",
        a.map.c_str(), map->keyframes().size(), map->local_maps(), map->voxel_count(),
        map->sessions(), map->path_length(), map->feature_count(),
        map->descriptors_computed() ? " (format 1: descriptors computed from the voxels)" : "",
        std::chrono::duration<double>(Clock::now() - t_load).count());

    sources::ScanFolderConfig fc;
    fc.path = a.dir;
    fc.format = sources::ScanFormat::kAuto;
    sources::ScanFolder folder(fc);
    const odometry::OdometryConfig oc = odometry::preset_config(preset);
    common::PoseList reference;
    if (!a.reference.empty()) {
        reference = common::read_kitti_poses(a.reference);
        if (!a.reference_transform.empty()) {
            const Eigen::Isometry3d T = read_transform(a.reference_transform);
            for (Eigen::Isometry3d& p : reference) p = T * p;
        }
        // The reference in the map's frame beside the attempts: ltm_eval reloc --attempts OUT
        // --reference OUT.reference.txt scores them (perturbed scans: their moved truth).
        if (!a.out.empty() && a.perturb_yaw <= 0.0 && a.perturb_shift <= 0.0)
            common::write_kitti_poses(a.out + ".reference.txt", reference);
    }
    std::size_t last = folder.size();
    if (a.max_frames) last = std::min(last, a.first + a.max_frames * a.every);
    std::vector<std::size_t> frames;
    for (std::size_t i = a.first; i < last; i += (a.mode == "track" ? 1 : a.every))
        frames.push_back(i);
    std::printf("%s: %zu scans, mode %s, preset %s%s\n", a.dir.c_str(), frames.size(),
                a.mode.c_str(), a.preset.c_str(),
                a.perturb_yaw > 0 || a.perturb_shift > 0 ? " (scans perturbed)" : "");

    std::ofstream out;
    if (!a.out.empty()) {
        out.open(a.out);
        if (!out) throw common::IoError(a.out, "cannot be written");
        out.precision(9);
    }
    std::ofstream traj;
    if (!a.trajectory.empty()) {
        traj.open(a.trajectory);
        if (!traj) throw common::IoError(a.trajectory, "cannot be written");
        traj.precision(9);
    }
    std::mt19937 rng(a.seed);
    std::uniform_real_distribution<double> uni(-1.0, 1.0);
    registration::Preprocessor pre(oc.preprocess, oc.voxel_size);
    registration::PreprocessedScan scan;
    odometry::Odometry odom(oc);
    localisation::Localiser localiser(map, lc);
    localisation::GlobalLocaliser global(map, lc.global);
    std::shared_ptr<localisation::NeighbourhoodBuilder> builder;
    std::size_t held_max = 0, held_sum = 0, held_n = 0;
    if (a.mode == "track" && a.hint_keyframe >= 0) {
        if (std::size_t(a.hint_keyframe) >= map->keyframes().size()) {
            std::fprintf(stderr, "ltm_bench_localise: --hint-keyframe: the map has %zu keyframes\n",
                         map->keyframes().size());
            return 2;
        }
        localiser.set_initial_pose(
            {map->keyframes()[std::size_t(a.hint_keyframe)].T_map_lidar, a.hint_radius});
    }
    if (map->paged()) {
        localisation::NeighbourhoodConfig nc;
        nc.radius = a.neighbourhood_radius;
        nc.rebuild_distance = a.rebuild_distance;
        const Eigen::Vector3d start = map->keyframes().front().T_map_lidar.translation();
        builder = std::make_shared<localisation::NeighbourhoodBuilder>(map->pages(), nc, start);
        localiser.set_neighbourhood(builder);
    }

    std::size_t ok = 0, right = 0, wrong = 0, none = 0, scored = 0;
    std::size_t near = 0, near_right = 0;  // scans within --near of a map keyframe
    std::vector<double> times, cpu_times, t_err, r_err;
    std::vector<double> step_times[5];  // global mode: the localiser's steps (StepTimes)
    std::vector<double> track_err;
    // Track mode: events (start, jumps of the reference) and when they were settled.
    struct Event {
        double at;
        double settled = -1.0;
        std::string what;
    };
    std::vector<Event> events;
    std::size_t relocalisations = 0, lost_scans = 0, off_map = 0;
    double process_s = 0.0, localise_s = 0.0;  // track mode: all, and the localiser alone
    common::Progress progress(a.mode, frames.size(), "scans");
    std::size_t heap_peak = 0;  // bytes in use (mallinfo2), sampled every 100 scans
    for (std::size_t n = 0; n < frames.size(); ++n) {
        if (n % 100 == 0) {
            // As the host gives the heap's free pages back (runtime/heap_trim.hpp), so that the
            // resident size says what is held.
            heap_peak = std::max(heap_peak, mallinfo2().uordblks);
            malloc_trim(0);
        }
        const std::size_t i = frames[n];
        Eigen::Isometry3d T_pert = Eigen::Isometry3d::Identity();
        const bool perturbed = a.perturb_yaw > 0 || a.perturb_shift > 0;
        if (perturbed) {
            T_pert.linear() =
                Eigen::AngleAxisd(uni(rng) * a.perturb_yaw * kDegToRad, Eigen::Vector3d::UnitZ())
                    .toRotationMatrix();
            const double r = a.perturb_shift * std::sqrt(0.5 * (uni(rng) + 1.0));
            const double th = uni(rng) * M_PI;
            T_pert.translation() = Eigen::Vector3d(r * std::cos(th), r * std::sin(th), 0.0);
        }
        // --only: the other frames' perturbations are drawn (the listed ones get theirs), no more.
        if (!a.only.empty() && std::find(a.only.begin(), a.only.end(), i) == a.only.end()) continue;
        common::PointCloud cloud = folder.load(i);
        if (perturbed) {
            const Eigen::Matrix3f R = T_pert.linear().cast<float>();
            const Eigen::Vector3f t = T_pert.translation().cast<float>();
            for (Eigen::Vector3f& p : cloud.points) p = R * p + t;
        }
        const bool have_ref = i < reference.size();
        const Eigen::Isometry3d truth = have_ref
                                            ? Eigen::Isometry3d(reference[i] * T_pert.inverse())
                                            : Eigen::Isometry3d::Identity();
        bool has_pose = false;
        Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
        double time_s = 0.0;
        const double cpu0 = cpu_seconds();
        double cpu_s = 0.0;
        if (a.mode == "global") {
            const auto t0 = Clock::now();
            pre.run(cloud, nullptr, &scan);
            const localisation::GlobalLocalisation g = global.localise(scan.map_points);
            time_s = std::chrono::duration<double>(Clock::now() - t0).count();
            cpu_s = cpu_seconds() - cpu0;
            const double steps[5] = {g.steps.places, g.steps.features, g.steps.probes,
                                     g.steps.verification, g.steps.checks};
            for (int k = 0; k < 5; ++k) step_times[k].push_back(steps[k]);
            has_pose = g.localised;
            pose = g.T_map_lidar;
            if (std::getenv("LTM_BENCH_VERBOSE"))
                std::printf("  %zu: cpu %.3f s (probes %.3f, verification %.3f, checks %.3f): %s\n",
                            i, cpu_s, g.steps.probes, g.steps.verification, g.steps.checks,
                            g.reason.c_str());
            if (a.verify_reference && have_ref) {
                const localisation::GlobalLocalisation v = global.verify(scan.map_points, truth);
                std::printf(
                    "  %zu at the reference (%.2f %.2f, yaw %.1f): %s (inliers %zu of %zu)\n", i,
                    truth.translation().x(), truth.translation().y(),
                    std::atan2(truth.linear()(1, 0), truth.linear()(0, 0)) / kDegToRad,
                    v.reason.c_str(), v.inliers, v.points);
            }
        } else {
            const auto t0 = Clock::now();
            const odometry::FrameResult r = odom.register_frame(cloud);
            pre.run(cloud, nullptr, &scan);
            std::optional<localisation::OdometryInput> oi;
            if (r.pose_valid()) oi = localisation::OdometryInput{r.T_odom_lidar, r.segment};
            const auto t1 = Clock::now();
            const localisation::LocalisationUpdate u =
                localiser.process(cloud.stamp, scan.map_points, oi);
            time_s = std::chrono::duration<double>(Clock::now() - t0).count();
            cpu_s = cpu_seconds() - cpu0;
            process_s += time_s;
            localise_s += std::chrono::duration<double>(Clock::now() - t1).count();
            has_pose = u.pose_valid;
            pose = u.T_map_lidar;
            if (builder) {
                if (a.settle) builder->settle();
                const std::size_t held = builder->current()->voxel_count();
                held_max = std::max(held_max, held);
                held_sum += held;
                ++held_n;
            }
            relocalisations += u.state == localisation::LocalisationState::kRelocalised;
            lost_scans += u.state == localisation::LocalisationState::kLost;
            off_map += u.state == localisation::LocalisationState::kOffMap;
            if (std::getenv("LTM_BENCH_VERBOSE") || u.global_ran ||
                u.state == localisation::LocalisationState::kLost) {
                if (!u.message.empty())
                    std::printf("  %zu (%.1f s) %s: %s\n", i, cloud.stamp,
                                localisation::to_string(u.state), u.message.c_str());
            }
            if (have_ref) {
                const bool jump =
                    n == 0 ||
                    (i > 0 && i - 1 < reference.size() &&
                     (reference[i].translation() - reference[i - 1].translation()).norm() > 5.0);
                if (jump) events.push_back({cloud.stamp, -1.0, n == 0 ? "start" : "jump"});
                if (has_pose && u.state != localisation::LocalisationState::kOffMap) {
                    const auto [et, er] = error_of(pose, truth);
                    if (et <= 0.1 && er <= 0.5 && !events.empty() && events.back().settled < 0)
                        events.back().settled = cloud.stamp;
                    if (u.state == localisation::LocalisationState::kTracking)
                        track_err.push_back(et);
                }
            }
        }
        times.push_back(time_s);
        cpu_times.push_back(cpu_s);
        if (out) write_line(out, i, time_s, has_pose, pose);
        if (traj && has_pose) {
            const Eigen::Quaterniond q(pose.linear());
            traj << cloud.stamp << ' ' << pose.translation().x() << ' ' << pose.translation().y()
                 << ' ' << pose.translation().z() << ' ' << q.x() << ' ' << q.y() << ' ' << q.z()
                 << ' ' << q.w() << '\n';
        }
        ok += has_pose;
        if (have_ref) {
            ++scored;
            const bool in_map = !map->keyframes_near(truth.translation(), a.near).empty();
            near += in_map;
            if (in_map && has_pose) {
                const auto [et, er] = error_of(pose, truth);
                near_right += et <= a.max_translation && er <= a.max_rotation;
            }
            if (!has_pose) {
                ++none;
            } else {
                const auto [et, er] = error_of(pose, truth);
                if (et <= a.max_translation && er <= a.max_rotation) {
                    ++right;
                    t_err.push_back(et);
                    r_err.push_back(er);
                } else {
                    ++wrong;
                    if (a.mode == "global")
                        std::printf("  wrong: scan %zu off by %.2f m / %.2f deg\n", i, et, er);
                }
            }
        }
        progress.update(n + 1);
    }
    progress.finish();
    std::printf("scans %zu, with a pose %zu (%.1f %%)\n", frames.size(), ok,
                frames.empty() ? 0.0 : 100.0 * double(ok) / double(frames.size()));
    if (scored) {
        std::printf(
            "against the reference (%.2f m / %.1f deg): right %zu (%.1f %%), wrong %zu, "
            "no pose %zu\n",
            a.max_translation, a.max_rotation, right, 100.0 * double(right) / double(scored), wrong,
            none);
        std::printf("scans within %.1f m of a map keyframe: %zu, right %zu (%.1f %%)\n", a.near,
                    near, near_right, near ? 100.0 * double(near_right) / double(near) : 0.0);
        std::printf(
            "error of the right ones: translation median %.3f m, 90 %% %.3f m; rotation "
            "median %.3f deg\n",
            percentile(t_err, 0.5), percentile(t_err, 0.9), percentile(r_err, 0.5));
    }
    std::printf("time a scan: median %.3f s, 90 %% %.3f s, max %.3f s\n", percentile(times, 0.5),
                percentile(times, 0.9), percentile(times, 1.0));
    std::printf("cpu a scan: median %.3f s, 90 %% %.3f s, max %.3f s\n", percentile(cpu_times, 0.5),
                percentile(cpu_times, 0.9), percentile(cpu_times, 1.0));
    if (a.mode == "global") {
        std::printf(
            "steps (wall, median): places %.3f s, features %.3f s, probes %.3f s, verification "
            "%.3f s, checks %.3f s\n",
            percentile(step_times[0], 0.5), percentile(step_times[1], 0.5),
            percentile(step_times[2], 0.5), percentile(step_times[3], 0.5),
            percentile(step_times[4], 0.5));
    }
    std::printf(
        "heap in use (main arena): %.1f MiB at the end, %.1f MiB at most (sampled every 100 "
        "scans); every arena: malloc_stats on stderr\n",
        double(mallinfo2().uordblks) / 1048576.0, double(heap_peak) / 1048576.0);
    std::fflush(stdout);
    malloc_stats();
    if (a.mode == "track") {
        std::printf(
            "track: %.1f scans/s (odometry + localisation, one thread), relocalisations "
            "%zu, lost scans %zu, off-map scans %zu\n",
            process_s > 0 ? double(frames.size()) / process_s : 0.0, relocalisations, lost_scans,
            off_map);
        std::printf("track: the localiser alone (tracking and its global queries) %.1f scans/s\n",
                    localise_s > 0 ? double(frames.size()) / localise_s : 0.0);
        if (builder) {
            std::printf(
                "track: neighbourhood radius %.0f m: %zu builds, voxels held for tracking mean "
                "%.0f, max %zu (the whole map %zu)\n",
                a.neighbourhood_radius, builder->builds(),
                held_n ? double(held_sum) / double(held_n) : 0.0, held_max, map->voxel_count());
            for (const std::string& r : builder->refused())
                std::printf("  refused: %s\n", r.c_str());
        }
        if (!track_err.empty()) {
            double sq = 0.0;
            for (double e : track_err) sq += e * e;
            std::printf(
                "tracking ATE (tracked scans, no alignment): rmse %.4f m over %zu scans, "
                "max %.3f m\n",
                std::sqrt(sq / double(track_err.size())), track_err.size(),
                percentile(track_err, 1.0));
        }
        for (const Event& e : events) {
            if (e.settled >= 0)
                std::printf("%s at %.1f s: localised within 0.1 m / 0.5 deg after %.2f s\n",
                            e.what.c_str(), e.at, e.settled - e.at);
            else
                std::printf("%s at %.1f s: NOT localised within 0.1 m / 0.5 deg\n", e.what.c_str(),
                            e.at);
        }
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    Args a;
    CLI::App app{"Localisation of a scan folder on a saved ltm map (global or track mode)",
                 "ltm_bench_localise"};
    app.add_option("DIR", a.dir, "the scans (KITTI layout or Scans/*.pcd; not in recall mode)");
    app.add_option("--map", a.map, "the saved map directory")->required();
    app.add_option("--reference", a.reference, "KITTI poses of the scans (LiDAR frame)");
    app.add_option("--reference-transform", a.reference_transform,
                   "one KITTI 3x4 line T_map_reference: maps the reference into the map's frame");
    app.add_option("--preset", a.preset, "sensor preset: hdl64, vlp32, vlp16, narrow or os1-64");
    app.add_option("--config", a.config,
                   "localisation keys overriding the preset (YAML, as the component's params)");
    app.add_option("--mode", a.mode,
                   "global: each scan alone; track: a sequence; recall: place recognition on the "
                   "map's keyframes (DIR unused)")
        ->check(common::cli::one_of({"global", "track", "recall"}));
    app.add_option("--revisit", a.revisit, "recall mode: a revisit is within this [m]");
    app.add_option("--exclude-seconds", a.exclude_seconds,
                   "recall mode: keyframes closer in time are not candidates [s]");
    app.add_option("--out", a.out,
                   "one line a scan: frame time_s ok [12 pose numbers] (ltm_eval reloc reads it; "
                   "with --reference, OUT.reference.txt holds the reference in the map's frame)");
    app.add_option("--trajectory", a.trajectory,
                   "the scans' poses in the map as TUM lines (those with a pose): ltm_eval traj");
    app.add_option("--every", a.every, "global mode: every Nth scan")
        ->check(common::cli::at_least(1));
    app.add_option("--first", a.first, "first scan");
    app.add_option("--max-frames", a.max_frames, "at most N scans (0: all)");
    app.add_option("--perturb-yaw", a.perturb_yaw,
                   "turn each scan by a random yaw within +-this [deg] (its truth moves with it)");
    app.add_option("--perturb-shift", a.perturb_shift,
                   "shift each scan by a random horizontal offset up to this [m]");
    app.add_option("--seed", a.seed, "random seed of the perturbations");
    app.add_option("--only", a.only,
                   "global mode: localise only these frames (of the --first/--every ones, with "
                   "the perturbations a whole run gives them)");
    app.add_option("--max-translation", a.max_translation, "a right answer: within [m]");
    app.add_option("--max-rotation", a.max_rotation, "a right answer: within [deg]");
    app.add_option("--near", a.near,
                   "also score the scans whose reference is within this of a map keyframe [m]");
    app.add_flag("--verify-reference", a.verify_reference,
                 "global mode: also verify each scan at its reference pose (is the map consistent "
                 "with the reference there?)");
    app.add_option("--neighbourhood-radius", a.neighbourhood_radius,
                   "the map paged: track on the local maps anchored within this of the pose, "
                   "read from the map directory as the robot moves, and verify a global query "
                   "on those within this of its initial poses [m] (0: the whole map in memory)");
    app.add_option("--rebuild-distance", a.rebuild_distance,
                   "track mode: a new neighbourhood when the pose moved this far [m]");
    app.add_flag("--settle", a.settle, "track mode: wait for each neighbourhood build");
    app.add_option("--hint-keyframe", a.hint_keyframe,
                   "track mode: the first global localisation narrowed to this map keyframe's "
                   "place (a map of look-alike copies: ltm_tile_map)");
    app.add_option("--hint-radius", a.hint_radius, "... within this of it [m]");
    app.add_flag("--no-features", a.no_features, "initial poses from the descriptors only");
    if (const int code = common::cli::parse(app, argc, argv); code >= 0) return code;
    if (a.dir.empty() && a.mode != "recall") {
        return common::cli::usage_error(
            app, common::cli::UsageError("DIR is required (the scans to localise)"));
    }
    try {
        return run(a);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "ltm_bench_localise: %s\n", e.what());
        return 1;
    }
}
