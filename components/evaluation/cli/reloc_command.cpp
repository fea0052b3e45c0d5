// ltm_eval reloc: relocalisation success rate and time against ground truth.
#include <iostream>

#include "evaluation/cli/args.hpp"
#include "evaluation/cli/commands.hpp"
#include "evaluation/cli/report.hpp"
#include "evaluation/cli/trajectory_input.hpp"
#include "evaluation/core/eval_io.hpp"
#include "evaluation/core/frames.hpp"
#include "evaluation/core/relocalisation.hpp"

namespace ltm::eval::cli {

const char* const kRelocUsage =
    "usage: ltm_eval reloc --attempts ATTEMPTS.txt --reference REF [options]\n"
    "  --attempts FILE            one attempt a line: `frame time_s ok [12 pose numbers]`\n"
    "                             (ok 1 with the KITTI 3x4 pose, 0 when it gave up)\n"
    "  --reference FILE           ground-truth poses (KITTI format), in the attempts' frame\n"
    "  --reference-frame lidar|camera, --calib FILE   (default lidar)\n"
    "  --max-translation M        success tolerance (default 0.5)\n"
    "  --max-rotation DEG         success tolerance (default 5)\n"
    "  --out DIR                  write metrics.txt, metrics.json\n";

int run_reloc(const std::vector<std::string>& argv) {
    const Args args(argv,
                    {"attempts", "reference", "reference-frame", "calib", "max-translation",
                     "max-rotation", "out"},
                    {});
    const std::string frame = args.choice("reference-frame", {"lidar", "camera"}, "lidar");
    const RelocAttempts attempts = read_reloc_attempts(args.required("attempts"));
    const common::PoseList ref =
        convert_frame(poses_of(load_trajectory(args.required("reference"), "kitti").poses), frame,
                      "lidar", args.get("calib"));
    RelocConfig config;
    config.max_translation = args.number("max-translation", config.max_translation);
    config.max_rotation_deg = args.number("max-rotation", config.max_rotation_deg);
    const RelocResult r = evaluate_relocalisation(attempts, ref, config);

    Report report("ltm_eval reloc: " + args.get("attempts"));
    report.section("input");
    report.add("max_translation", config.max_translation, "m");
    report.add("max_rotation", config.max_rotation_deg, "deg");
    report.add_count("out_of_range_excluded", r.out_of_range);
    report.section("relocalisation");
    report.add_count("attempts", r.attempts);
    report.add_count("successes", r.successes);
    report.add_count("wrong_pose", r.wrong);
    report.add_count("no_pose", r.no_pose);
    report.add("success_rate", r.success_rate);
    report.add("time_mean_all", r.time_all_s.mean, "s");
    report.add("time_median_all", r.time_all_s.median, "s");
    report.add("time_max_all", r.time_all_s.max, "s");
    report.add("time_mean_success", r.time_success_s.mean, "s");
    report.add("time_median_success", r.time_success_s.median, "s");
    report.add("translation_error_mean_success", r.translation_error.mean, "m");
    report.add("rotation_error_mean_success", r.rotation_error_deg.mean, "deg");
    std::cout << report.text();
    if (args.has("out")) report.write(args.get("out"));
    return 0;
}

}  // namespace ltm::eval::cli
