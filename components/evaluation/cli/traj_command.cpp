// ltm_eval traj: ATE, RPE and the KITTI metric of an estimated trajectory, with figures.
#include <filesystem>
#include <iostream>
#include <memory>

#include "common/core/trajectory_io.hpp"
#include "evaluation/cli/commands.hpp"
#include "evaluation/cli/report.hpp"
#include "evaluation/cli/trajectory_input.hpp"
#include "evaluation/core/ate.hpp"
#include "evaluation/core/eval_io.hpp"
#include "evaluation/core/figures.hpp"
#include "evaluation/core/frames.hpp"
#include "evaluation/core/kitti_metric.hpp"
#include "evaluation/core/place_recognition.hpp"
#include "evaluation/core/rpe.hpp"

namespace ltm::eval::cli {

namespace {

struct TrajOptions {
    std::string estimate, reference, format = "kitti", estimate_format, reference_format;
    double max_dt = 0.02;
    std::string estimate_frame = "lidar", reference_frame = "lidar", eval_frame = "lidar", calib;
    long frames = -1;  // all
    long delta = 1;
    bool no_align = false;
    std::string loops;
    PlaceRecognitionConfig loop_scoring;
    std::string plane, title, out;
};

int run_traj(const TrajOptions& o);

}  // namespace

Run add_traj(CLI::App& parent) {
    CLI::App* app = parent.add_subcommand("traj", "trajectory: ATE, RPE, KITTI metric, figures");
    auto o = std::make_shared<TrajOptions>();
    const auto formats = common::cli::one_of({"kitti", "tum"});
    const auto frames = common::cli::one_of({"lidar", "camera"});
    app->add_option("--estimate", o->estimate, "estimated poses")->required();
    app->add_option("--reference", o->reference, "reference poses")->required();
    app->add_option("--format", o->format,
                    "both files' format (kitti: pose i = frame i; tum: poses paired by nearest "
                    "stamp within --max-dt)")
        ->check(formats);
    app->add_option("--estimate-format", o->estimate_format, "the estimate's (default --format)")
        ->check(formats);
    app->add_option("--reference-format", o->reference_format, "the reference's (default --format)")
        ->check(formats);
    app->add_option("--max-dt", o->max_dt, "TUM pairing tolerance [s]");
    app->add_option("--estimate-frame", o->estimate_frame, "frame of the estimate")->check(frames);
    app->add_option("--reference-frame", o->reference_frame,
                    "frame of the reference (KITTI ground truth is camera)")
        ->check(frames);
    app->add_option("--eval-frame", o->eval_frame, "frame the metrics are computed in")
        ->check(frames);
    app->add_option("--calib", o->calib, "KITTI calibration (Tr) for frame conversions");
    app->add_option("--frames", o->frames, "only the first N pose pairs")
        ->default_str("all")
        ->check(common::cli::at_least(0));
    app->add_option("--delta", o->delta, "RPE frame delta")->check(common::cli::at_least(1));
    app->add_flag("--no-align", o->no_align, "ATE without the Umeyama SE(3) alignment");
    app->add_option("--loops", o->loops, "detected loops `query match [score]`: drawn, and scored");
    app->add_option("--revisit-radius", o->loop_scoring.revisit_radius, "loop scoring [m]");
    app->add_option("--min-gap", o->loop_scoring.min_frame_gap, "loop scoring [frames]");
    app->add_option("--plane", o->plane,
                    "top-view plane (default xy in the lidar, xz in the camera frame)")
        ->check(common::cli::one_of({"auto", "xy", "xz", "yz"}));
    app->add_option("--title", o->title, "figure title");
    app->add_option("--out", o->out,
                    "write metrics.txt, metrics.json, trajectory.svg, errors.svg, "
                    "estimate_aligned.txt here");
    return [o] { return run_traj(*o); };
}

namespace {

int run_traj(const TrajOptions& o) {
    const std::string est_format = o.estimate_format.empty() ? o.format : o.estimate_format;
    const std::string ref_format = o.reference_format.empty() ? o.format : o.reference_format;
    const std::string& est_frame = o.estimate_frame;
    const std::string& ref_frame = o.reference_frame;
    const std::string& eval_frame = o.eval_frame;
    const std::string& calib = o.calib;
    const long max_frames = o.frames;
    const long delta = o.delta;
    const bool align = !o.no_align;

    const LoadedTrajectory est_in = load_trajectory(o.estimate, est_format);
    const LoadedTrajectory ref_in = load_trajectory(o.reference, ref_format);
    common::PoseList est, ref;
    Report report("ltm_eval traj: " + o.estimate + " vs " + o.reference);
    report.section("input");
    if (est_in.stamped && ref_in.stamped) {
        const PairedPoses paired = pair_by_stamp(est_in.poses, ref_in.poses, o.max_dt);
        est = paired.estimate;
        ref = paired.reference;
        report.add_count("unpaired_estimate_poses", paired.unmatched);
    } else {
        if (est_in.stamped != ref_in.stamped)
            report.note("one file is TUM, the other KITTI: poses paired by index");
        est = poses_of(est_in.poses);
        ref = poses_of(ref_in.poses);
        if (est.size() != ref.size() && max_frames < 0)
            report.note("estimate has " + std::to_string(est.size()) + " poses, reference " +
                        std::to_string(ref.size()) + ": compared over the first " +
                        std::to_string(std::min(est.size(), ref.size())));
    }
    std::size_t n = std::min(est.size(), ref.size());
    if (max_frames >= 0) n = std::min<std::size_t>(n, static_cast<std::size_t>(max_frames));
    est.resize(n);
    ref.resize(n);
    if (n < 2) throw UsageError("fewer than 2 pose pairs to compare");
    est = convert_frame(est, est_frame, eval_frame, calib);
    ref = convert_frame(ref, ref_frame, eval_frame, calib);
    const std::vector<double> dist = distances_travelled(ref);
    report.add_count("pose_pairs", n);
    report.add("reference_length", dist.back(), "m");
    report.add_text("eval_frame", eval_frame);

    const AteDetail ate = compute_ate_detail(est, ref, align);
    report.section(align ? "ate_se3_aligned" : "ate_unaligned");
    report.add("rmse", ate.stats.rmse, "m");
    report.add("mean", ate.stats.mean, "m");
    report.add("median", ate.stats.median, "m");
    report.add("max", ate.stats.max, "m");

    const RpeResult rpe = compute_rpe(est, ref, static_cast<std::size_t>(delta));
    report.section("rpe_delta_" + std::to_string(delta) + "_frames");
    report.add("translation_rmse", rpe.translation.rmse, "m");
    report.add("translation_mean", rpe.translation.mean, "m");
    report.add("translation_max", rpe.translation.max, "m");
    report.add("rotation_rmse", rpe.rotation_deg.rmse, "deg");
    report.add("rotation_mean", rpe.rotation_deg.mean, "deg");
    report.add("rotation_max", rpe.rotation_deg.max, "deg");

    const KittiMetric kitti = kitti_metric_for_lengths(est, ref, kitti_lengths());
    report.section("kitti_100_800m");
    report.add_count("segments", kitti.segments);
    if (kitti.segments > 0) {
        report.add("translation", kitti.translation_pct, "%");
        report.add("rotation", kitti.rotation_deg_per_100m, "deg/100m");
    } else {
        report.note("no segment: the run is shorter than 100 m");
    }
    if (dist.back() < 800.0) {
        const KittiMetric s = kitti_metric_for_lengths(est, ref, kitti_short_lengths());
        report.section("kitti_short_10_50m");
        report.note(
            "run under 800 m: KITTI definition over 10..50 m segments (not comparable "
            "with the benchmark's 100..800 m figures)");
        report.add_count("segments", s.segments);
        if (s.segments > 0) {
            report.add("translation", s.translation_pct, "%");
            report.add("rotation", s.rotation_deg_per_100m, "deg/100m");
        }
    }

    std::vector<LoopPair> loops;
    std::vector<bool> loop_correct;
    if (!o.loops.empty()) {
        loops = read_loop_pairs(o.loops);
        const PlaceRecognitionResult pr = evaluate_loops(loops, ref, o.loop_scoring);
        loop_correct = pr.correct;
        report.section("loops");
        report.add_count("detected", pr.detected);
        report.add_count("true_positives", pr.true_positives);
        report.add_count("revisit_queries", pr.revisit_queries);
        report.add("precision", pr.precision);
        report.add("recall", pr.recall);
        report.add("f1", pr.f1);
    }

    std::cout << report.text();
    if (o.out.empty()) return 0;
    const std::filesystem::path out = o.out;
    report.write(out.string());
    common::write_kitti_poses((out / "estimate_aligned.txt").string(),
                              transform_poses(ate.T_ref_est, est));

    TrajectoryFigure tf;
    tf.title = o.title.empty() ? "Trajectory top view (" + eval_frame + " frame)" : o.title;
    tf.reference = ref;
    tf.estimate = transform_poses(ate.T_ref_est, est);
    tf.loops = loops;
    tf.loop_correct = loop_correct;
    const std::string plane = !o.plane.empty() ? o.plane : eval_frame == "camera" ? "xz" : "xy";
    tf.plane = plane == "xy"   ? TopViewPlane::kXY
               : plane == "xz" ? TopViewPlane::kXZ
               : plane == "yz" ? TopViewPlane::kYZ
                               : TopViewPlane::kAuto;
    write_text_file((out / "trajectory.svg").string(), trajectory_svg(tf));

    ErrorFigure ef;
    ef.title = o.title.empty() ? "Error along the trajectory" : o.title;
    ef.distance = dist;
    ef.position_error = ate.errors;
    rpe_errors(est, ref, 1, ef.step_translation, ef.step_rotation_deg);
    write_text_file((out / "errors.svg").string(), errors_svg(ef));
    std::cout << "wrote " << (out / "metrics.txt").string() << ", metrics.json, trajectory.svg, "
              << "errors.svg, estimate_aligned.txt\n";
    return 0;
}

}  // namespace
}  // namespace ltm::eval::cli
