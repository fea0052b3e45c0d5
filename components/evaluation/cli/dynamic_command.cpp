// ltm_eval dynamic: SA / DA / AA of a cleaned map against per-point labels.
#include <algorithm>
#include <filesystem>
#include <iostream>

#include "common/core/io_error.hpp"
#include "common/core/kitti_io.hpp"
#include "common/core/pcl_cloud_io.hpp"
#include "common/core/ply_io.hpp"
#include "common/core/progress.hpp"
#include "evaluation/cli/args.hpp"
#include "evaluation/cli/commands.hpp"
#include "evaluation/cli/report.hpp"
#include "evaluation/cli/trajectory_input.hpp"
#include "evaluation/core/dynamic_removal.hpp"
#include "evaluation/core/eval_io.hpp"

namespace ltm::eval::cli {

const char* const kDynamicUsage =
    "usage: ltm_eval dynamic --map CLEANED.pcd|.ply (--scans SEQ_DIR | --truth GT.pcd|.ply)\n"
    "  --map FILE               the output map to score (world frame)\n"
    "  --scans DIR              KITTI-layout run: DIR/velodyne/*.bin, DIR/labels/*.label\n"
    "  --labels DIR             label folder (default DIR/labels)\n"
    "  --poses FILE             scan poses (default DIR/poses.txt), KITTI format\n"
    "  --poses-frame lidar|camera  frame of the poses (default lidar; camera needs the calib)\n"
    "  --calib FILE             KITTI calib.txt (default DIR/calib.txt)\n"
    "  --label-scheme ltm|semantickitti  (default ltm: class 2 = moving actor)\n"
    "  --changed-is-dynamic     count objects changed between sessions (class 3) as dynamic\n"
    "  --first N, --count N     scans used (default all that have labels)\n"
    "  --max-range M            skip points farther from the sensor (default 0: none; the\n"
    "                           DynamicMap benchmark uses 50 for SemanticKITTI)\n"
    "  --truth FILE             instead of scans: a labelled map, intensity 1 = dynamic\n"
    "                           (the DynamicMap benchmark's gt_cloud.pcd)\n"
    "  --match-distance M       kept if an output point is this near (default 0.05)\n"
    "  --write-truth FILE.ply   write the labelled truth map (intensity 1 = dynamic)\n"
    "  --write-static FILE.ply  write its static points (a perfect cleaned map)\n"
    "  --out DIR                write metrics.txt, metrics.json\n";

namespace {

LabelledMap truth_from_scans(const Args& args, Report& report) {
    const std::string dir = args.get("scans");
    const std::vector<std::string> scans = common::list_kitti_scans(dir);
    const std::string seq = common::kitti_sequence_dir(dir);
    const std::filesystem::path label_dir =
        args.get("labels", (std::filesystem::path(seq) / "labels").string());
    const std::string scheme_name = args.choice("label-scheme", {"ltm", "semantickitti"}, "ltm");
    const common::LabelScheme scheme =
        scheme_name == "ltm" ? common::LabelScheme::kLtmSim : common::LabelScheme::kSemanticKitti;
    const std::string calib =
        args.get("calib", (std::filesystem::path(seq) / "calib.txt").string());
    const std::string poses_frame = args.choice("poses-frame", {"lidar", "camera"}, "lidar");
    const common::PoseList poses =
        convert_frame(common::read_kitti_poses(
                          args.get("poses", (std::filesystem::path(seq) / "poses.txt").string())),
                      poses_frame, "lidar", poses_frame == "camera" ? calib : "");

    const auto first = static_cast<std::size_t>(std::max(0L, args.integer("first", 0)));
    std::size_t end = scans.size();
    if (args.has("count"))
        end = std::min(end, first + static_cast<std::size_t>(args.integer("count", 0)));
    const double max_range = args.number("max-range", 0.0);
    const bool changed = args.has("changed-is-dynamic");

    const auto label_of = [&](std::size_t i) {
        return (label_dir / (std::filesystem::path(scans[i]).stem().string() + ".label")).string();
    };
    // Without --count: the scans up to the first one with no label file (SemanticKITTI
    // snippets label only their first frames).
    for (std::size_t i = first; i < end; ++i) {
        if (std::filesystem::exists(label_of(i))) continue;
        if (args.has("count")) throw common::IoError(label_of(i), "missing label file");
        end = i;
    }

    LabelledMap map;
    std::size_t used = 0;
    common::Progress progress("labelled scans", end > first ? end - first : 0, "scans");
    for (std::size_t i = first; i < end; ++i) {
        const std::filesystem::path scan(scans[i]);
        const std::string label_path = label_of(i);
        const std::size_t frame = static_cast<std::size_t>(std::stoul(scan.stem().string()));
        if (frame >= poses.size()) throw common::IoError(scans[i], "no pose for this scan");
        const common::PointCloud cloud = common::read_kitti_bin(scans[i]);
        const std::vector<std::uint32_t> labels = read_labels(label_path);
        if (!append_labelled_scan(cloud, labels, poses[frame], scheme, changed, max_range, map))
            throw common::IoError(label_path, std::to_string(labels.size()) + " labels for " +
                                                  std::to_string(cloud.size()) + " points");
        ++used;
        progress.update(i + 1 - first);
    }
    progress.finish();
    if (used == 0) throw UsageError("no scan with a label file in " + label_dir.string());
    report.add_count("scans", used);
    report.add_text("label_scheme", scheme_name);
    return map;
}

LabelledMap truth_from_cloud(const std::string& path) {
    const common::PointCloud cloud = common::load_cloud_file(path);
    if (!cloud.has_intensity())
        throw common::IoError(path, "the truth map needs an intensity label");
    LabelledMap map;
    map.points = cloud.points;
    for (float v : cloud.intensity) map.dynamic.push_back(v > 0.5f ? 1 : 0);
    return map;
}

void write_cloud(const std::string& path, const LabelledMap& map, bool static_only) {
    common::PlyCloud ply;
    for (std::size_t i = 0; i < map.points.size(); ++i) {
        if (static_only && map.dynamic[i]) continue;
        ply.points.push_back(map.points[i]);
        ply.intensity.push_back(static_cast<float>(map.dynamic[i]));
    }
    common::write_ply(path, ply);
}

}  // namespace

int run_dynamic(const std::vector<std::string>& argv) {
    const Args args(
        argv,
        {"map", "scans", "labels", "poses", "poses-frame", "calib", "label-scheme", "first",
         "count", "max-range", "truth", "match-distance", "write-truth", "write-static", "out"},
        {"changed-is-dynamic"});
    if (args.has("scans") == args.has("truth"))
        throw UsageError("give either --scans DIR or --truth FILE");
    Report report("ltm_eval dynamic: " + args.get("map", "(no map)"));
    report.section("input");
    const LabelledMap truth =
        args.has("scans") ? truth_from_scans(args, report) : truth_from_cloud(args.get("truth"));
    if (args.has("write-truth")) write_cloud(args.get("write-truth"), truth, false);
    if (args.has("write-static")) write_cloud(args.get("write-static"), truth, true);
    if (!args.has("map")) {
        if (args.has("write-truth") || args.has("write-static")) return 0;
        throw UsageError("--map is required");
    }
    const common::PointCloud output = common::load_cloud_file(args.get("map"));
    DynamicRemovalConfig config;
    config.match_distance = args.number("match-distance", config.match_distance);
    if (config.match_distance <= 0.0) throw UsageError("--match-distance must be positive");
    const DynamicRemovalResult r = evaluate_dynamic_removal(truth, output.points, config);

    report.add_count("truth_points", truth.points.size());
    report.add_count("map_points", output.points.size());
    report.add("match_distance", config.match_distance, "m");
    report.section("dynamic_removal");
    report.add_count("static_points", r.static_points);
    report.add_count("static_kept", r.static_kept);
    report.add_count("dynamic_points", r.dynamic_points);
    report.add_count("dynamic_removed", r.dynamic_removed);
    report.add("SA", r.sa_pct, "%");
    report.add("DA", r.da_pct, "%");
    report.add("AA", r.aa_pct, "%");
    report.add("HA", r.ha_pct, "%");
    if (r.dynamic_points == 0) report.note("no dynamic point in the truth: DA, AA, HA are 0");
    std::cout << report.text();
    if (args.has("out")) report.write(args.get("out"));
    return 0;
}

}  // namespace ltm::eval::cli
