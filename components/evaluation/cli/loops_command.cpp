// ltm_eval loops: precision, recall and F1 of detected loops against ground-truth revisits.
#include <filesystem>
#include <iostream>

#include "evaluation/cli/args.hpp"
#include "evaluation/cli/commands.hpp"
#include "evaluation/cli/report.hpp"
#include "evaluation/cli/trajectory_input.hpp"
#include "evaluation/core/ate.hpp"
#include "evaluation/core/eval_io.hpp"
#include "evaluation/core/figures.hpp"
#include "evaluation/core/frames.hpp"
#include "evaluation/core/place_recognition.hpp"

namespace ltm::eval::cli {

const char* const kLoopsUsage =
    "usage: ltm_eval loops --loops LOOPS.txt --reference REF [options]\n"
    "  --loops FILE               one loop a line: `query match [score]` (frame indices)\n"
    "  --reference FILE           ground-truth poses of the query session (KITTI format)\n"
    "  --match-reference FILE     cross-session loops: ground truth of the matched session, in\n"
    "                             the same world frame (no frame gap applies)\n"
    "  --reference-frame lidar|camera, --calib FILE   frame of the poses (default lidar)\n"
    "  --revisit-radius M         same place within this distance (default 5)\n"
    "  --min-gap N                within a session, loops need this many frames (default 50)\n"
    "  --estimate FILE            estimated poses: the figure draws loops on them (aligned)\n"
    "  --out DIR                  write metrics.txt, metrics.json, loops.svg\n";

int run_loops(const std::vector<std::string>& argv) {
    const Args args(argv,
                    {"loops", "reference", "match-reference", "reference-frame", "calib",
                     "revisit-radius", "min-gap", "estimate", "out"},
                    {});
    const std::string frame = args.choice("reference-frame", {"lidar", "camera"}, "lidar");
    const auto load = [&](const std::string& path) {
        return convert_frame(poses_of(load_trajectory(path, "kitti").poses), frame, "lidar",
                             args.get("calib"));
    };
    const std::vector<LoopPair> loops = read_loop_pairs(args.required("loops"));
    const common::PoseList ref = load(args.required("reference"));
    PlaceRecognitionConfig config;
    config.revisit_radius = args.number("revisit-radius", config.revisit_radius);
    const long gap = args.integer("min-gap", static_cast<long>(config.min_frame_gap));
    if (gap < 0) throw UsageError("--min-gap must not be negative");
    config.min_frame_gap = static_cast<std::size_t>(gap);

    const bool cross = args.has("match-reference");
    const PlaceRecognitionResult r =
        cross ? evaluate_cross_session_loops(loops, ref, load(args.get("match-reference")), config)
              : evaluate_loops(loops, ref, config);
    Report report("ltm_eval loops: " + args.get("loops"));
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
    if (!args.has("out")) return 0;
    report.write(args.get("out"));
    if (!cross) {
        TrajectoryFigure f;
        f.title = "Detected loops (green true, red false)";
        f.reference = ref;
        f.estimate = ref;
        if (args.has("estimate")) {
            common::PoseList est = load(args.get("estimate"));
            f.estimate = transform_poses(compute_ate_detail(est, ref).T_ref_est, est);
        }
        f.loops = loops;
        f.loop_correct = r.correct;
        f.plane = TopViewPlane::kXY;
        write_text_file((std::filesystem::path(args.get("out")) / "loops.svg").string(),
                        trajectory_svg(f));
    }
    return 0;
}

}  // namespace ltm::eval::cli
