// ltm_eval traj: ATE, RPE and the KITTI metric of an estimated trajectory, with figures.
#include <filesystem>
#include <iostream>

#include "common/core/trajectory_io.hpp"
#include "evaluation/cli/args.hpp"
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

const char* const kTrajUsage =
    "usage: ltm_eval traj --estimate EST --reference REF [options]\n"
    "  --format kitti|tum          both files' format (default kitti: pose i = frame i;\n"
    "                              tum: poses paired by nearest stamp within --max-dt)\n"
    "  --estimate-format F, --reference-format F   per file\n"
    "  --max-dt S                  TUM pairing tolerance [s] (default 0.02)\n"
    "  --estimate-frame lidar|camera, --reference-frame lidar|camera   frames of the files\n"
    "                              (default lidar; KITTI ground truth is camera)\n"
    "  --eval-frame lidar|camera   frame the metrics are computed in (default lidar)\n"
    "  --calib calib.txt           KITTI calibration (Tr) for frame conversions\n"
    "  --frames N                  only the first N pose pairs\n"
    "  --delta N                   RPE frame delta (default 1)\n"
    "  --no-align                  ATE without the Umeyama SE(3) alignment\n"
    "  --loops FILE                detected loops `query match [score]`: drawn, and scored\n"
    "  --revisit-radius M, --min-gap N   loop scoring (default 5 m, 50 frames)\n"
    "  --plane auto|xy|xz|yz       top-view plane (default xy in lidar, xz in camera frame)\n"
    "  --title TEXT                figure title\n"
    "  --out DIR                   write metrics.txt, metrics.json, trajectory.svg, errors.svg,\n"
    "                              estimate_aligned.txt\n";

int run_traj(const std::vector<std::string>& argv) {
    const Args args(argv,
                    {"estimate", "reference", "format", "estimate-format", "reference-format",
                     "max-dt", "estimate-frame", "reference-frame", "eval-frame", "calib", "frames",
                     "delta", "loops", "revisit-radius", "min-gap", "plane", "title", "out"},
                    {"no-align"});
    const std::string format = args.choice("format", {"kitti", "tum"}, "kitti");
    const std::string est_format = args.choice("estimate-format", {"kitti", "tum"}, format);
    const std::string ref_format = args.choice("reference-format", {"kitti", "tum"}, format);
    const std::vector<std::string> frames{"lidar", "camera"};
    const std::string est_frame = args.choice("estimate-frame", frames, "lidar");
    const std::string ref_frame = args.choice("reference-frame", frames, "lidar");
    const std::string eval_frame = args.choice("eval-frame", frames, "lidar");
    const std::string calib = args.get("calib");
    const long max_frames = args.integer("frames", -1);
    const long delta = args.integer("delta", 1);
    if (delta < 1) throw UsageError("--delta must be at least 1");
    const bool align = !args.has("no-align");

    const LoadedTrajectory est_in = load_trajectory(args.required("estimate"), est_format);
    const LoadedTrajectory ref_in = load_trajectory(args.required("reference"), ref_format);
    common::PoseList est, ref;
    Report report("ltm_eval traj: " + args.get("estimate") + " vs " + args.get("reference"));
    report.section("input");
    if (est_in.stamped && ref_in.stamped) {
        const PairedPoses paired =
            pair_by_stamp(est_in.poses, ref_in.poses, args.number("max-dt", 0.02));
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
    if (args.has("loops")) {
        loops = read_loop_pairs(args.get("loops"));
        PlaceRecognitionConfig pc;
        pc.revisit_radius = args.number("revisit-radius", pc.revisit_radius);
        pc.min_frame_gap = static_cast<std::size_t>(args.integer("min-gap", 50));
        const PlaceRecognitionResult pr = evaluate_loops(loops, ref, pc);
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
    if (!args.has("out")) return 0;
    const std::filesystem::path out = args.get("out");
    report.write(out.string());
    common::write_kitti_poses((out / "estimate_aligned.txt").string(),
                              transform_poses(ate.T_ref_est, est));

    TrajectoryFigure tf;
    tf.title = args.get("title", "Trajectory top view (" + eval_frame + " frame)");
    tf.reference = ref;
    tf.estimate = transform_poses(ate.T_ref_est, est);
    tf.loops = loops;
    tf.loop_correct = loop_correct;
    const std::string plane =
        args.choice("plane", {"auto", "xy", "xz", "yz"}, eval_frame == "camera" ? "xz" : "xy");
    tf.plane = plane == "xy"   ? TopViewPlane::kXY
               : plane == "xz" ? TopViewPlane::kXZ
               : plane == "yz" ? TopViewPlane::kYZ
                               : TopViewPlane::kAuto;
    write_text_file((out / "trajectory.svg").string(), trajectory_svg(tf));

    ErrorFigure ef;
    ef.title = args.get("title", "Error along the trajectory");
    ef.distance = dist;
    ef.position_error = ate.errors;
    rpe_errors(est, ref, 1, ef.step_translation, ef.step_rotation_deg);
    write_text_file((out / "errors.svg").string(), errors_svg(ef));
    std::cout << "wrote " << (out / "metrics.txt").string() << ", metrics.json, trajectory.svg, "
              << "errors.svg, estimate_aligned.txt\n";
    return 0;
}

}  // namespace ltm::eval::cli
