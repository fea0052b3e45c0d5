// ltm_eval loops: precision, recall and F1 of detected loops against ground-truth revisits.
#include <filesystem>
#include <iostream>
#include <memory>

#include "evaluation/cli/commands.hpp"
#include "evaluation/cli/report.hpp"
#include "evaluation/cli/trajectory_input.hpp"
#include "evaluation/core/ate.hpp"
#include "evaluation/core/eval_io.hpp"
#include "evaluation/core/figures.hpp"
#include "evaluation/core/frames.hpp"
#include "evaluation/core/place_recognition.hpp"

namespace ltm::eval::cli {

namespace {

struct LoopsOptions {
    std::string loops, reference, match_reference, reference_frame = "lidar", calib, estimate, out;
    PlaceRecognitionConfig config;
};

int run_loops(const LoopsOptions& o) {
    const auto load = [&](const std::string& path) {
        return convert_frame(poses_of(load_trajectory(path, "kitti").poses), o.reference_frame,
                             "lidar", o.calib);
    };
    const std::vector<LoopPair> loops = read_loop_pairs(o.loops);
    const common::PoseList ref = load(o.reference);
    const PlaceRecognitionConfig& config = o.config;

    const bool cross = !o.match_reference.empty();
    const PlaceRecognitionResult r =
        cross ? evaluate_cross_session_loops(loops, ref, load(o.match_reference), config)
              : evaluate_loops(loops, ref, config);
    Report report("ltm_eval loops: " + o.loops);
    report.section("input");
    report.add_text("mode", cross ? "cross-session" : "single session");
    report.add_count("loops_in_file", loops.size());
    report.add("revisit_radius", config.revisit_radius, "m");
    if (!cross) report.add_count("min_frame_gap", config.min_frame_gap);
    report.section("place_recognition");
    report.add_count("detected", r.detected);
    report.add_count("true_positives", r.true_positives);
    report.add_count("false_positives", r.false_positives);
    report.add_count("trivial_excluded", r.trivial);
    report.add_count("out_of_range_excluded", r.out_of_range);
    report.add_count("revisit_queries", r.revisit_queries);
    report.add_count("recalled_queries", r.recalled_queries);
    report.add("precision", r.precision);
    report.add("recall", r.recall);
    report.add("f1", r.f1);
    std::cout << report.text();
    if (o.out.empty()) return 0;
    report.write(o.out);
    if (!cross) {
        TrajectoryFigure f;
        f.title = "Detected loops (green true, red false)";
        f.reference = ref;
        f.estimate = ref;
        if (!o.estimate.empty()) {
            common::PoseList est = load(o.estimate);
            f.estimate = transform_poses(compute_ate_detail(est, ref).T_ref_est, est);
        }
        f.loops = loops;
        f.loop_correct = r.correct;
        f.plane = TopViewPlane::kXY;
        write_text_file((std::filesystem::path(o.out) / "loops.svg").string(), trajectory_svg(f));
    }
    return 0;
}

}  // namespace

Run add_loops(CLI::App& parent) {
    CLI::App* app = parent.add_subcommand("loops", "place recognition: precision, recall, F1");
    auto o = std::make_shared<LoopsOptions>();
    app->add_option("--loops", o->loops, "one loop a line: `query match [score]` (frame indices)")
        ->required();
    app->add_option("--reference", o->reference,
                    "ground-truth poses of the query session (KITTI format)")
        ->required();
    app->add_option("--match-reference", o->match_reference,
                    "cross-session loops: ground truth of the matched session, in the same world "
                    "frame (no frame gap applies)");
    app->add_option("--reference-frame", o->reference_frame, "frame of the poses")
        ->check(common::cli::one_of({"lidar", "camera"}));
    app->add_option("--calib", o->calib, "KITTI calib.txt for the camera frame");
    app->add_option("--revisit-radius", o->config.revisit_radius, "same place within this [m]");
    app->add_option("--min-gap", o->config.min_frame_gap,
                    "within a session, loops need this many frames");
    app->add_option("--estimate", o->estimate,
                    "estimated poses: the figure draws loops on them (aligned)");
    app->add_option("--out", o->out, "write metrics.txt, metrics.json, loops.svg here");
    return [o] { return run_loops(*o); };
}

}  // namespace ltm::eval::cli
