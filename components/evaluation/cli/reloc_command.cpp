// ltm_eval reloc: relocalisation success rate and time against ground truth.
#include <iostream>
#include <memory>

#include "evaluation/cli/commands.hpp"
#include "evaluation/cli/report.hpp"
#include "evaluation/cli/trajectory_input.hpp"
#include "evaluation/core/eval_io.hpp"
#include "evaluation/core/frames.hpp"
#include "evaluation/core/relocalisation.hpp"

namespace ltm::eval::cli {

namespace {

struct RelocOptions {
    std::string attempts, reference, reference_frame = "lidar", calib, out;
    RelocConfig config;
};

int run_reloc(const RelocOptions& o) {
    const RelocAttempts attempts = read_reloc_attempts(o.attempts);
    const common::PoseList ref = convert_frame(
        poses_of(load_trajectory(o.reference, "kitti").poses), o.reference_frame, "lidar", o.calib);
    const RelocConfig& config = o.config;
    const RelocResult r = evaluate_relocalisation(attempts, ref, config);

    Report report("ltm_eval reloc: " + o.attempts);
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
    if (!o.out.empty()) report.write(o.out);
    return 0;
}

}  // namespace

Run add_reloc(CLI::App& parent) {
    CLI::App* app = parent.add_subcommand("reloc", "relocalisation success rate and time");
    auto o = std::make_shared<RelocOptions>();
    app->add_option("--attempts", o->attempts,
                    "one attempt a line: `frame time_s ok [12 pose numbers]` (ok 1 with the KITTI "
                    "3x4 pose, 0 when it gave up)")
        ->required();
    app->add_option("--reference", o->reference,
                    "ground-truth poses (KITTI format), in the attempts' frame")
        ->required();
    app->add_option("--reference-frame", o->reference_frame, "frame of the poses")
        ->check(common::cli::one_of({"lidar", "camera"}));
    app->add_option("--calib", o->calib, "KITTI calib.txt for the camera frame");
    app->add_option("--max-translation", o->config.max_translation, "success tolerance [m]");
    app->add_option("--max-rotation", o->config.max_rotation_deg, "success tolerance [deg]");
    app->add_option("--out", o->out, "write metrics.txt, metrics.json here");
    return [o] { return run_reloc(*o); };
}

}  // namespace ltm::eval::cli
