// ltm_eval report: one self-contained report.html of a run folder (what `./ltm run`, the demo and
// the benchmarks with --out write): what ran, trajectories and their errors, a top view of the
// map and its changes, the localisation's status over time, the figures, and every file.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>

#include "common/core/file_io.hpp"
#include "common/core/io_error.hpp"
#include "common/core/trajectory_io.hpp"
#include "evaluation/cli/commands.hpp"
#include "evaluation/cli/run_folder.hpp"
#include "evaluation/core/ate.hpp"
#include "evaluation/core/figures.hpp"
#include "evaluation/core/frames.hpp"
#include "evaluation/core/html_report.hpp"
#include "evaluation/core/localisation_timeline.hpp"
#include "evaluation/core/mesh_io.hpp"
#include "evaluation/core/png_image.hpp"
#include "evaluation/core/rpe.hpp"
#include "evaluation/core/top_view_image.hpp"

namespace ltm::eval::cli {

namespace fs = std::filesystem;

namespace {

constexpr double kPathGap =
    1.0;  // [s] a longer gap between poses (a kidnap, a restart): not joined

struct ReportOptions {
    std::string run_dir, out, title, reference;
    double max_dt = 0.02;
};

std::string fixed(double v, int digits) {
    std::ostringstream s;
    s.setf(std::ios::fixed);
    s.precision(digits);
    s << v;
    return s.str();
}

double path_length(const common::Trajectory& t) {
    double length = 0.0;
    for (std::size_t i = 1; i < t.size(); ++i)
        length += (t[i].pose.translation() - t[i - 1].pose.translation()).norm();
    return length;
}

void what_ran(const RunFolder& run, HtmlReport& report) {
    report.section("What ran");
    std::vector<std::vector<std::string>> rows;
    rows.push_back({"folder", run.dir});
    for (const auto& [key, value] : run.run_record) rows.push_back({key, value});
    if (!run.launch_line.empty()) rows.push_back({"launch", run.launch_line});
    if (!run.components_line.empty()) rows.push_back({"host", run.components_line});
    if (!run.exit_status.empty()) rows.push_back({"exit status", run.exit_status});
    rows.push_back({"warnings / errors in host.log",
                    std::to_string(run.warnings) + " / " + std::to_string(run.errors)});
    report.table({"", ""}, rows);
    if (!run.problem_lines.empty()) {
        std::string text;
        for (const std::string& l : run.problem_lines) text += l + "\n";
        report.collapsed("host.log: warnings and errors (first " +
                             std::to_string(run.problem_lines.size()) + ")",
                         text);
    }
    if (!run.launch_copy.empty()) {
        try {
            report.collapsed("the launch config (launch.yaml)",
                             common::read_file(run.launch_copy, run.launch_copy));
        } catch (const common::IoError& e) {
            report.paragraph(e.what());
        }
    }
    if (run.host_log.empty()) {
        report.paragraph(
            "No host.log in this folder: the host's log went where its output did "
            "(./ltm run ... 2> LTM_OUT/host.log keeps it for the report).");
    }
}

struct Scored {
    std::string name;
    common::Trajectory estimate;
    PairedPoses pairs;
    AteDetail ate;
};

// Figures of every trajectory and, with a reference, its errors and pictures.
std::vector<Scored> trajectories(const RunFolder& run, const ReportOptions& o,
                                 const common::Trajectory& reference, HtmlReport& report) {
    report.section("Trajectories");
    std::vector<Scored> scored;
    std::vector<std::vector<std::string>> rows;
    for (const auto& [name, path] : run.trajectories) {
        Scored s;
        s.name = name;
        try {
            s.estimate = common::read_tum_trajectory(path);
        } catch (const common::IoError& e) {
            rows.push_back({name, "unreadable: " + std::string(e.what())});
            continue;
        }
        std::vector<std::string> row = {name, std::to_string(s.estimate.size()),
                                        fixed(path_length(s.estimate), 1)};
        if (!reference.empty() && !s.estimate.empty()) {
            s.pairs = pair_by_stamp(s.estimate, reference, o.max_dt);
            if (s.pairs.estimate.size() >= 3) {
                s.ate = compute_ate_detail(s.pairs.estimate, s.pairs.reference);
                row.push_back(std::to_string(s.pairs.estimate.size()));
                row.push_back(fixed(s.ate.stats.rmse, 3));
                row.push_back(fixed(s.ate.stats.median, 3));
                row.push_back(fixed(s.ate.stats.max, 3));
            }
        }
        rows.push_back(row);
        scored.push_back(std::move(s));
    }
    if (rows.empty()) {
        report.paragraph("No trajectory (*_tum.txt) in this folder.");
        return scored;
    }
    if (reference.empty()) {
        report.paragraph(
            "No reference trajectory (ground_truth_tum.txt or --reference): lengths only.");
        report.table({"trajectory", "poses", "length [m]"}, rows);
        return scored;
    }
    report.paragraph("Errors against " + o.reference +
                     " after one rigid (SE(3), no scale) "
                     "alignment per trajectory, poses paired by stamp within " +
                     fixed(o.max_dt, 3) + " s.");
    report.table(
        {"trajectory", "poses", "length [m]", "paired", "ATE rmse [m]", "median [m]", "max [m]"},
        rows);
    for (const Scored& s : scored) {
        if (s.pairs.estimate.size() < 3) continue;
        TrajectoryFigure top;
        top.title = s.name + " (aligned) and the reference";
        top.reference = s.pairs.reference;
        top.estimate = transform_poses(s.ate.T_ref_est, s.pairs.estimate);
        report.svg(trajectory_svg(top), s.name + ": top view against the reference");
        ErrorFigure errors;
        errors.title = s.name + ": error along the trajectory";
        double d = 0.0;
        for (std::size_t i = 0; i < s.pairs.reference.size(); ++i) {
            if (i > 0) {
                d += (s.pairs.reference[i].translation() - s.pairs.reference[i - 1].translation())
                         .norm();
            }
            errors.distance.push_back(d);
        }
        errors.position_error = s.ate.errors;
        rpe_errors(s.pairs.estimate, s.pairs.reference, 1, errors.step_translation,
                   errors.step_rotation_deg);
        report.svg(errors_svg(errors), s.name + ": position error and frame-to-frame error");
    }
    return scored;
}

void map_view(const RunFolder& run, const std::vector<Scored>& scored,
              const common::Trajectory& reference, HtmlReport& report) {
    report.section("Map");
    std::vector<TopViewLayer> layers;
    std::vector<std::string> described;
    for (const std::string& path : run.map_clouds) {
        try {
            ColouredCloud cloud = read_coloured_cloud(path);
            TopViewLayer layer;
            layer.label = fs::relative(path, run.dir).string();
            layer.points = std::move(cloud.points);
            described.push_back(layer.label + " (" + std::to_string(layer.points.size()) +
                                " points, grey by density)");
            layers.push_back(std::move(layer));
        } catch (const common::IoError& e) {
            report.paragraph(std::string("Map cloud not drawn: ") + e.what());
        }
    }
    for (const std::string& path : run.change_clouds) {
        try {
            ColouredCloud cloud = read_coloured_cloud(path);
            TopViewLayer layer;
            layer.label = fs::relative(path, run.dir).string();
            layer.points = std::move(cloud.points);
            layer.colours.assign(cloud.colours.begin(), cloud.colours.end());
            if (layer.colours.empty()) layer.colour = {214, 39, 40};
            described.push_back(layer.label + " (" + std::to_string(layer.points.size()) +
                                " voxels: removed red, added green)");
            layers.push_back(std::move(layer));
        } catch (const common::IoError& e) {
            report.paragraph(std::string("Changes not drawn: ") + e.what());
        }
    }
    std::vector<TopViewPath> paths;
    // The map frame's own trajectory, every scan where there is one: the last found of odometry,
    // slam, map poses, localisation wins. The reference is drawn in its frame (the trajectory's
    // alignment to it, inverted), so nothing moves the map.
    const Scored* best = nullptr;
    for (const char* preferred : {"odometry", "slam", "map_poses", "localisation"}) {
        for (const Scored& s : scored) {
            if (s.name == preferred) best = &s;
        }
    }
    if (best == nullptr && !scored.empty()) best = &scored.front();
    if (best != nullptr && !reference.empty() && best->pairs.estimate.size() >= 3) {
        TopViewPath ref;
        ref.label = "reference";
        ref.colour = {150, 150, 150};
        const Eigen::Isometry3d T_est_ref = best->ate.T_ref_est.inverse();
        for (std::size_t i = 0; i < reference.size(); ++i) {
            if (i > 0 && reference[i].stamp - reference[i - 1].stamp > kPathGap) {
                ref.positions.push_back(Eigen::Vector3d::Constant(NAN));
            }
            ref.positions.push_back(T_est_ref * reference[i].pose.translation());
        }
        described.push_back("the reference in grey, in the map frame by " + best->name +
                            "'s alignment");
        paths.push_back(std::move(ref));
    }
    if (best != nullptr) {
        TopViewPath est;
        est.label = best->name;
        for (std::size_t i = 0; i < best->estimate.size(); ++i) {
            if (i > 0 && best->estimate[i].stamp - best->estimate[i - 1].stamp > kPathGap) {
                est.positions.push_back(Eigen::Vector3d::Constant(NAN));
            }
            est.positions.push_back(best->estimate[i].pose.translation());
        }
        described.push_back(best->name + " in blue (as written; gaps over " + fixed(kPathGap, 0) +
                            " s not joined)");
        paths.push_back(std::move(est));
    }
    if (layers.empty()) {
        report.paragraph(
            "No map picture: this run wrote no global_map.ply (the mapping's "
            "global_map_file) and no maintenance changes PLY.");
        if (paths.empty()) return;
    }
    const TopView view = render_top_view(layers, paths, 1100);
    if (view.image.width == 0) {
        report.paragraph("Nothing to draw (no finite point).");
        return;
    }
    std::string caption = "Top view, " + fixed(view.metres_per_pixel, 3) + " m a pixel: ";
    for (std::size_t i = 0; i < described.size(); ++i) caption += (i ? "; " : "") + described[i];
    report.png(encode_png(view.image), caption);
}

void localisation(const RunFolder& run, HtmlReport& report) {
    if (run.status_streams.empty()) return;
    report.section("Localisation");
    for (const StatusStream& stream : run.status_streams) {
        const TimelineSummary t = summarise_timeline(stream.samples);
        report.paragraph(stream.topic + " in " + fs::relative(stream.file, run.dir).string() +
                         ": " + std::to_string(t.samples) + " scans over " +
                         fixed(t.end - t.start, 1) + " s" +
                         (stream.problem.empty() ? "" : " (" + stream.problem + ")"));
        if (t.samples == 0) continue;
        std::vector<std::vector<std::string>> rows;
        for (int s = 0; s < kStatusStates; ++s) {
            rows.push_back({status_state_name(static_cast<std::uint8_t>(s)),
                            std::to_string(t.in_state[s]),
                            fixed(100.0 * t.in_state[s] / t.samples, 1)});
        }
        rows.push_back(
            {"pose valid", std::to_string(t.valid), fixed(100.0 * t.valid / t.samples, 1)});
        report.table({"state", "scans", "%"}, rows);
        report.table({"global queries", "median [s]", "max [s]", "re-localisations", "losses",
                      "scans skipped"},
                     {{std::to_string(t.global_queries), fixed(t.global_median, 3),
                       fixed(t.global_max, 3), std::to_string(t.relocalisations.size()),
                       std::to_string(t.losses.size()), std::to_string(t.skipped_scans)}});
        report.svg(timeline_svg(stream.samples, "Localisation state"),
                   "The localisation's state at every scan, and its confidence");
        std::vector<std::vector<std::string>> events;
        for (const auto& e : t.relocalisations) {
            if (events.size() >= 50) break;
            events.push_back({fixed(e.stamp - t.start, 1), "re-localised", e.message});
        }
        for (const auto& e : t.losses) {
            if (events.size() >= 100) break;
            events.push_back({fixed(e.stamp - t.start, 1), "lost", e.message});
        }
        std::sort(events.begin(), events.end(),
                  [](const auto& a, const auto& b) { return std::stod(a[0]) < std::stod(b[0]); });
        if (!events.empty()) report.table({"time [s]", "event", "message"}, events);
    }
}

void text_files(const RunFolder& run, HtmlReport& report) {
    if (run.text_reports.empty()) return;
    report.section("Numbers");
    for (const std::string& path : run.text_reports) {
        std::string text;
        try {
            text = common::read_file(path, path);
        } catch (const common::IoError& e) {
            text = e.what();
        }
        if (text.size() > 20000) text = text.substr(0, 20000) + "\n[... cut at 20 kB]";
        report.collapsed(fs::relative(path, run.dir).string(), text);
    }
}

int run_report(const ReportOptions& options) {
    ReportOptions o = options;
    if (!fs::is_directory(o.run_dir)) throw UsageError("report: no such run folder: " + o.run_dir);
    if (o.out.empty()) o.out = (fs::path(o.run_dir) / "report.html").string();
    const RunFolder run = scan_run_folder(o.run_dir);
    if (o.reference.empty()) o.reference = run.reference;
    common::Trajectory reference;
    if (!o.reference.empty()) reference = common::read_tum_trajectory(o.reference);

    HtmlReport report(o.title.empty() ? "ltm run: " + fs::path(run.dir).filename().string()
                                      : o.title);
    what_ran(run, report);
    const std::vector<Scored> scored = trajectories(run, o, reference, report);
    map_view(run, scored, reference, report);
    localisation(run, report);
    if (!run.maintenance_summary.empty()) {
        report.section("Map maintenance");
        report.paragraph(run.maintenance_summary);
    }
    if (!run.figures.empty()) {
        report.section("Figures");
        for (const std::string& path : run.figures) {
            try {
                report.svg(common::read_file(path, path), fs::relative(path, run.dir).string());
            } catch (const common::IoError& e) {
                report.paragraph(e.what());
            }
        }
    }
    text_files(run, report);
    report.section("Files");
    report.files(run.files);
    common::write_file_atomic(o.out, report.html());
    std::cout << "report: " << o.out << "\n";
    return 0;
}

}  // namespace

Run add_report(CLI::App& parent) {
    CLI::App* app = parent.add_subcommand(
        "report", "a run folder's report.html: what ran, trajectories, map, localisation, files");
    auto o = std::make_shared<ReportOptions>();
    app->add_option("run_dir", o->run_dir, "the run's output folder (LTM_OUT)")->required();
    app->add_option("--out", o->out, "the report (default RUN_DIR/report.html)");
    app->add_option("--title", o->title, "the report's title");
    app->add_option("--reference", o->reference,
                    "reference trajectory, TUM (default RUN_DIR/ground_truth_tum.txt if there)");
    app->add_option("--max-dt", o->max_dt, "TUM pairing tolerance [s]");
    return [o] { return run_report(*o); };
}

}  // namespace ltm::eval::cli
