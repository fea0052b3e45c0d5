// ltm_eval dynamic: SA / DA / AA of a cleaned map against per-point labels, and DA per object.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>

#include "common/core/io_error.hpp"
#include "common/core/kitti_io.hpp"
#include "common/core/pcl_cloud_io.hpp"
#include "common/core/ply_io.hpp"
#include "common/core/progress.hpp"
#include "evaluation/cli/commands.hpp"
#include "evaluation/cli/report.hpp"
#include "evaluation/cli/trajectory_input.hpp"
#include "evaluation/core/dynamic_removal.hpp"
#include "evaluation/core/eval_io.hpp"

namespace ltm::eval::cli {

namespace {

struct DynamicOptions {
    std::string map, scans, labels, poses, poses_frame = "lidar", calib, label_scheme = "ltm";
    bool changed_is_dynamic = false;
    std::size_t first = 0, count = 0, every = 1;
    bool has_count = false;
    double max_range = 0.0;
    std::string truth;
    DynamicRemovalConfig config;
    std::string write_truth, write_static, out;
};

LabelledMap truth_from_scans(const DynamicOptions& o, Report& report) {
    const std::string& dir = o.scans;
    const std::vector<std::string> scans = common::list_kitti_scans(dir);
    const std::string seq = common::kitti_sequence_dir(dir);
    const std::filesystem::path label_dir =
        o.labels.empty() ? std::filesystem::path(seq) / "labels" : std::filesystem::path(o.labels);
    const std::string& scheme_name = o.label_scheme;
    const common::LabelScheme scheme =
        scheme_name == "ltm" ? common::LabelScheme::kLtmSim : common::LabelScheme::kSemanticKitti;
    const std::string calib =
        o.calib.empty() ? (std::filesystem::path(seq) / "calib.txt").string() : o.calib;
    const std::string& poses_frame = o.poses_frame;
    const common::PoseList poses = convert_frame(
        common::read_kitti_poses(
            o.poses.empty() ? (std::filesystem::path(seq) / "poses.txt").string() : o.poses),
        poses_frame, "lidar", poses_frame == "camera" ? calib : "");

    const std::size_t first = o.first;
    std::size_t end = scans.size();
    if (o.has_count) end = std::min(end, first + o.count);
    const double max_range = o.max_range;
    const bool changed = o.changed_is_dynamic;

    const auto label_of = [&](std::size_t i) {
        return (label_dir / (std::filesystem::path(scans[i]).stem().string() + ".label")).string();
    };
    // Without --count: the scans up to the first one with no label file (SemanticKITTI
    // snippets label only their first frames).
    for (std::size_t i = first; i < end; ++i) {
        if (std::filesystem::exists(label_of(i))) continue;
        if (o.has_count) throw common::IoError(label_of(i), "missing label file");
        end = i;
    }

    LabelledMap map;
    std::size_t used = 0;
    common::Progress progress("labelled scans", end > first ? end - first : 0, "scans");
    for (std::size_t i = first; i < end; i += std::max<std::size_t>(1, o.every)) {
        const std::filesystem::path scan(scans[i]);
        const std::string label_path = label_of(i);
        const std::size_t frame = static_cast<std::size_t>(std::stoul(scan.stem().string()));
        if (frame >= poses.size()) throw common::IoError(scans[i], "no pose for this scan");
        const common::PointCloud cloud = common::read_kitti_bin(scans[i]);
        const std::vector<std::uint32_t> labels = read_labels(label_path);
        if (!append_labelled_scan(cloud, labels, poses[frame], scheme, changed, max_range,
                                  static_cast<std::uint32_t>(frame), map))
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

std::string format(const char* fmt, double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, fmt, v);
    return buf;
}

std::string pad_left(std::string s, std::size_t width) {
    return s.size() < width ? std::string(width - s.size(), ' ') + s : s;
}

// The per-object view: totals over the objects that travel at least min_travel, then a table.
void report_objects(const DynamicRemovalResult& r, double min_travel, Report& report) {
    report.section("moving_objects");
    report.add("min_travel", min_travel, "m");
    report.add_count("all_objects", r.objects.size());
    report.add_count("objects", r.moving_objects);
    report.add_count("points", r.moving_points);
    report.add_count("removed", r.moving_removed);
    report.add("DA", r.moving_da_pct, "%");
    report.note("DA of moving objects >= " + format("%g", min_travel) + " m: " +
                format("%.2f", r.moving_da_pct) + " % over " + std::to_string(r.moving_objects) +
                " objects, " + std::to_string(r.moving_points) + " points");
    if (r.objects.empty()) return;
    report.note("    id  class      frames  travel [m]    points  removed [%]");
    bool unnamed = false;
    for (const DynamicObject& d : r.objects) {
        unnamed = unnamed || d.instance == 0;
        const std::string frames = std::to_string(d.first_frame) + "-" +
                                   std::to_string(d.last_frame) + " (" + std::to_string(d.frames) +
                                   ")";
        report.note(
            pad_left(std::to_string(d.instance), 6) + pad_left(std::to_string(d.label_class), 7) +
            pad_left(frames, 12) + pad_left(format("%.2f", d.travel), 12) +
            pad_left(std::to_string(d.points), 10) + pad_left(format("%.1f", d.removed_pct), 13));
    }
    if (unnamed) report.note("id 0: the points of that class that have no instance id");
    if (r.static_losses.empty()) return;
    report.note("static objects that lost the most points:");
    report.note("    id  class    points  lost  lost [%]");
    for (const DynamicObject& d : r.static_losses)
        report.note(
            pad_left(std::to_string(d.instance), 6) + pad_left(std::to_string(d.label_class), 7) +
            pad_left(std::to_string(d.points), 10) + pad_left(std::to_string(d.removed), 6) +
            pad_left(format("%.1f", d.removed_pct), 10));
}

// The per-object table as a JSON array.
std::string objects_json(const std::vector<DynamicObject>& objects) {
    std::string out = "[";
    for (std::size_t i = 0; i < objects.size(); ++i) {
        const DynamicObject& d = objects[i];
        out += std::string(i > 0 ? "," : "") + "\n    {\"id\": " + std::to_string(d.instance) +
               ", \"class\": " + std::to_string(d.label_class) +
               ", \"first_frame\": " + std::to_string(d.first_frame) +
               ", \"last_frame\": " + std::to_string(d.last_frame) +
               ", \"frames\": " + std::to_string(d.frames) +
               ", \"travel_m\": " + format("%.6g", d.travel) +
               ", \"points\": " + std::to_string(d.points) +
               ", \"removed\": " + std::to_string(d.removed) +
               ", \"removed_pct\": " + format("%.6g", d.removed_pct) + "}";
    }
    return out + (objects.empty() ? "]" : "\n  ]");
}

// metrics.txt as the report prints it; metrics.json with the per-object array added last.
void write_report(const std::string& dir, const Report& report,
                  const std::vector<DynamicObject>& objects, bool with_objects) {
    std::string json = report.json();
    if (with_objects) {
        // Report::json() ends with "}\n": the array goes before that closing brace.
        const std::size_t close = json.rfind('}');
        const std::size_t last = json.find_last_not_of(" \n", close - 1);
        json.insert(last + 1, ",\n  \"dynamic_objects\": " + objects_json(objects));
    }
    write_text_file((std::filesystem::path(dir) / "metrics.txt").string(), report.text());
    write_text_file((std::filesystem::path(dir) / "metrics.json").string(), json);
}

int run_dynamic(const DynamicOptions& o) {
    if (o.scans.empty() == o.truth.empty())
        throw UsageError("give either --scans DIR or --truth FILE");
    Report report("ltm_eval dynamic: " + (o.map.empty() ? "(no map)" : o.map));
    report.section("input");
    const LabelledMap truth =
        !o.scans.empty() ? truth_from_scans(o, report) : truth_from_cloud(o.truth);
    if (!o.write_truth.empty()) write_cloud(o.write_truth, truth, false);
    if (!o.write_static.empty()) write_cloud(o.write_static, truth, true);
    if (o.map.empty()) {
        if (!o.write_truth.empty() || !o.write_static.empty()) return 0;
        throw UsageError("--map", "is required");
    }
    const common::PointCloud output = common::load_cloud_file(o.map);
    const DynamicRemovalConfig& config = o.config;
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
    const bool per_object = !truth.labels.empty();
    if (per_object)
        report_objects(r, config.min_travel, report);
    else
        report.note("no per-object view: it needs --scans (per-point labels)");
    std::cout << report.text();
    if (!o.out.empty()) write_report(o.out, report, r.objects, per_object);
    return 0;
}

}  // namespace

Run add_dynamic(CLI::App& parent) {
    CLI::App* app = parent.add_subcommand("dynamic", "dynamic-object removal: SA, DA, AA");
    app->footer("Give --scans (a labelled KITTI-layout run) or --truth (a labelled map).");
    auto o = std::make_shared<DynamicOptions>();
    app->add_option("--map", o->map, "the output map to score (world frame), .pcd or .ply");
    app->add_option("--scans", o->scans,
                    "KITTI-layout run: DIR/velodyne/*.bin, DIR/labels/*.label");
    app->add_option("--labels", o->labels, "label folder (default DIR/labels)");
    app->add_option("--poses", o->poses, "scan poses, KITTI format (default DIR/poses.txt)");
    app->add_option("--poses-frame", o->poses_frame, "frame of the poses (camera needs the calib)")
        ->check(common::cli::one_of({"lidar", "camera"}));
    app->add_option("--calib", o->calib, "KITTI calib.txt (default DIR/calib.txt)");
    app->add_option("--label-scheme", o->label_scheme, "ltm: class 2 = moving actor")
        ->check(common::cli::one_of({"ltm", "semantickitti"}));
    app->add_flag("--changed-is-dynamic", o->changed_is_dynamic,
                  "count objects changed between sessions (class 3) as dynamic");
    app->add_option("--first", o->first, "first scan used");
    app->add_option("--every", o->every, "every Nth scan from --first (long simulated sessions)")
        ->check(common::cli::at_least(1));
    app->add_option("--count", o->count, "scans used (default: all that have labels)")
        ->default_str("")
        ->each([o](const std::string&) { o->has_count = true; });
    app->add_option("--max-range", o->max_range,
                    "skip points farther from the sensor (0: none; the DynamicMap benchmark uses "
                    "50 for SemanticKITTI)");
    app->add_option("--truth", o->truth,
                    "instead of scans: a labelled map, intensity 1 = dynamic (the DynamicMap "
                    "benchmark's gt_cloud.pcd)");
    app->add_option("--match-distance", o->config.match_distance,
                    "kept if an output point is this near [m]")
        ->check(common::cli::positive());
    app->add_option("--min-travel", o->config.min_travel,
                    "DA is also reported over the objects (class and instance id) whose centroid "
                    "travels at least this far between their first and last scan [m]")
        ->check(common::cli::at_least(0.0));
    app->add_option("--write-truth", o->write_truth,
                    "write the labelled truth map (.ply, intensity 1 = dynamic)");
    app->add_option("--write-static", o->write_static,
                    "write its static points (.ply, a perfect cleaned map)");
    app->add_option("--out", o->out, "write metrics.txt, metrics.json here");
    return [o] { return run_dynamic(*o); };
}

}  // namespace ltm::eval::cli
