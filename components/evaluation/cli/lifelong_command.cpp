// ltm_eval lifelong: every day of a lifelong benchmark run scored against the simulator's truth,
// one row a day (the layout of a run's folder: components/bench/lifelong/README.md).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>

#include "common/core/io_error.hpp"
#include "common/core/ply_io.hpp"
#include "common/core/trajectory_io.hpp"
#include "evaluation/cli/commands.hpp"
#include "evaluation/cli/lifelong_inputs.hpp"
#include "evaluation/cli/report.hpp"
#include "evaluation/core/ate.hpp"
#include "evaluation/core/lifelong_figure.hpp"
#include "evaluation/core/lifelong_poses.hpp"
#include "evaluation/core/map_change_score.hpp"
#include "evaluation/core/new_ground.hpp"
#include "evaluation/core/object_account.hpp"

namespace ltm::eval::cli {

namespace {

namespace fs = std::filesystem;

struct LifelongOptions {
    std::string run, out;
    int days = 0;
    DayPoseConfig poses;
    NewGroundConfig ground;
    MapChangeConfig changes;
    double min_health = 0.0, min_planarity = 0.4;
};

std::string day_dir(const LifelongOptions& o, int d) {
    return (fs::path(o.run) / ("day" + std::to_string(d))).string();
}

std::string need(const std::string& path) {
    if (!fs::exists(path)) throw common::IoError(path, "missing (see ltm_eval lifelong --help)");
    return path;
}

double percent(std::size_t part, std::size_t whole) {
    return whole == 0 ? 0.0 : 100.0 * static_cast<double>(part) / static_cast<double>(whole);
}

std::string fmt(const char* f, double v) {
    char text[48];
    std::snprintf(text, sizeof text, f, v);
    return text;
}

// "87.5% of 96": the share of `before` voxels the later map no longer has; "-" without any.
std::string gone_text(std::size_t kept, std::size_t before) {
    if (before == 0) return "-";
    return fmt("%.1f%%", 100.0 - percent(kept, before)) + " of " + std::to_string(before);
}

// "93.1%/150": the share of the places' voxels gone, of how many; "-" without any.
std::string gone_short(const AccountTotals& t) {
    if (t.before == 0) return "-";
    return fmt("%.1f%%", 100.0 - percent(t.kept, t.before)) + "/" + std::to_string(t.before);
}

std::string objects_text(const std::vector<ObjectAccount>& accounts) {
    std::ostringstream out;
    out << "# id kind what left route_m voxels_day0 at_start after kept_z  (left: today = it "
           "stood there the day before; route_m: nearest scan of the day to its centre; voxels of "
           "the place in day 0's map, the map the day started from and the map after it; kept_z: "
           "median height of the voxels kept above the object's base [m])\n";
    for (const auto& a : accounts) {
        char line[200];
        std::snprintf(line, sizeof line, "%u %s %s %s %.1f %zu %zu %zu %.2f\n", a.object.id,
                      a.object.kind.c_str(), a.what.c_str(), a.today ? "today" : "earlier",
                      a.route_distance, a.before, a.at_start, a.kept, a.kept_median_height);
        out << line;
    }
    return out.str();
}

// Every voxel of a left place (a removed object's, a moved object's first place: in its box grown
// by the margin, at least the ground clearance above its base) that the later map has
// (dayN_kept.txt): where it is (world and map frame), how high above the object's base and above
// the lowest voxel of the later map within 0.5 m horizontally (0: the lowest there, the ground as
// the map has it), whether day 0's map had a voxel within 0.2 m, and which object standing on the
// day has it in its grown box (-: none). Which voxels stay, and where.
std::string kept_text(const ObjectChanges& changes, const std::vector<SiteObject>& today,
                      const std::vector<Eigen::Vector3d>& first,
                      const std::vector<Eigen::Vector3d>& later,
                      const Eigen::Isometry3d& T_world_map, const MapChangeConfig& config) {
    std::ostringstream out;
    out << "# id what x y z (world) mx my mz (map frame) above_base above_lowest_near in_day0 "
           "standing [m]\n";
    const Eigen::Isometry3d T_map_world = T_world_map.inverse();
    auto place = [&](const SiteObject& o, const char* what) {
        for (const auto& p : later) {
            if (!o.contains(p, config.box_margin) ||
                p.z() < o.ground_at(p) + config.ground_clearance)
                continue;
            double lowest = p.z();
            for (const auto& q : later)
                if (std::hypot(q.x() - p.x(), q.y() - p.y()) <= 0.5)
                    lowest = std::min(lowest, q.z());
            const bool in_first = std::any_of(first.begin(), first.end(),
                                              [&](const auto& q) { return (q - p).norm() <= 0.2; });
            std::string standing = "-";
            for (const auto& s : today)
                if (s.id != o.id && s.contains(p, config.box_margin))
                    standing = std::to_string(s.id);
            const Eigen::Vector3d m = T_map_world * p;
            char line[240];
            std::snprintf(line, sizeof line,
                          "%u %s %.2f %.2f %.2f %.2f %.2f %.2f %.2f %.2f %d %s\n", o.id, what,
                          p.x(), p.y(), p.z(), m.x(), m.y(), m.z(), p.z() - o.base_z,
                          p.z() - lowest, in_first ? 1 : 0, standing.c_str());
            out << line;
        }
    };
    for (const auto& o : changes.removed) place(o, "removed");
    for (const auto& o : changes.moved_from) place(o, "moved");
    return out.str();
}

std::string kidnap_text(const DayPoseScore& s) {
    if (s.kidnaps.empty()) return "-";
    std::string out;
    for (const auto& k : s.kidnaps) {
        if (!out.empty()) out += ",";
        out += k.recovered ? fmt("%.1fs", k.time_s) : std::string("never");
        if (k.wrong > 0) out += "(" + std::to_string(k.wrong) + "w)";
    }
    return out;
}

int run_lifelong(const LifelongOptions& o) {
    // The one alignment: day 0's final SLAM keyframes against day 0's truth.
    const common::Trajectory truth0 =
        common::read_tum_trajectory(need(day_dir(o, 0) + "/truth/poses_tum.txt"));
    const MapAlignment align = fit_map_alignment(
        common::read_tum_trajectory(need(day_dir(o, 0) + "/slam_tum.txt")), truth0, o.poses.max_dt);
    if (align.matched < 3)
        throw common::IoError(day_dir(o, 0) + "/slam_tum.txt",
                              "fewer than 3 keyframes match the truth by stamp");

    // The same with one scale fitted: a diagnostic of the map's scale (see MapSimilarity).
    const MapSimilarity sim = fit_map_similarity(
        common::read_tum_trajectory(need(day_dir(o, 0) + "/slam_tum.txt")), truth0, o.poses.max_dt);
    std::ostringstream scaled;
    scaled
        << "with scale (a diagnostic, not the targets' alignment): the one alignment fitted with "
           "one scale too on day 0's keyframes: the map is "
        << fmt("%+.3f", 100.0 * (1.0 / sim.scale - 1.0)) << " % against the truth, keyframes rmse "
        << fmt("%.3f", sim.rmse)
        << " m (a map's scale is what no loop observes; what remains is what loops and ties can "
           "remove)\n"
        << "day rmse_s  p95_s  max_s  >0.5m\n";
    std::vector<std::vector<SiteObject>> objects;
    std::vector<SiteObject> unstable;
    for (int d = 0; d < o.days; ++d) {
        objects.push_back(read_site_objects(need(day_dir(o, d) + "/truth/objects.txt")));
        for (const auto& ob : objects.back())
            if (ob.changed) unstable.push_back(ob);
    }
    const std::string first_map_dir = day_dir(o, 0) + "/next_map";
    const std::vector<Eigen::Vector3d> first_map =
        fs::exists(first_map_dir)
            ? map_voxel_centres(first_map_dir, align.T_world_map, o.min_health, o.min_planarity)
            : std::vector<Eigen::Vector3d>{};

    Report report("ltm_eval lifelong: " + o.run);
    report.section("alignment");
    report.add_count("day0_keyframes_matched", align.matched);
    report.add("day0_keyframes_rmse", align.ate.rmse, "m");
    report.add("day0_keyframes_scale", sim.scale);
    report.add("day0_keyframes_rmse_scaled", sim.rmse, "m");
    std::ostringstream table;
    table << "day0 final SLAM keyframes vs truth (the one alignment): rmse "
          << fmt("%.3f", align.ate.rmse) << " m over " << align.matched << " keyframes\n";
    char header[512];
    std::snprintf(header, sizeof header,
                  "%3s %5s %6s %6s %6s %6s %6s  %-16s %9s  %-13s %-11s %-12s %-12s %-12s "
                  "%-12s %9s %7s %7s %7s %8s %7s %6s\n",
                  "day", "scans", "pose%", "rmse", "p95", "max", ">0.5m", "kidnap->correct",
                  "new/mapped", "removed_gone", "moved_gone", "rm_today", "rm_earlier", "mv_today",
                  "mv_earlier", "moved_new", "added", "static%", "map_MB", "maint_MB", "peak_MB",
                  "cpu_ms");
    table << header;
    std::vector<Eigen::Vector3d> earlier, start_map;
    for (int d = 0; d < o.days; ++d) {
        const std::string dir = day_dir(o, d);
        const common::Trajectory truth =
            d == 0 ? truth0 : common::read_tum_trajectory(need(dir + "/truth/poses_tum.txt"));
        const DayPoseScore s = score_day_poses(
            common::read_tum_trajectory(need(dir + "/map_poses_tum.txt")), truth, align.T_world_map,
            read_kidnap_stamps(need(dir + "/truth/kidnaps.txt")), o.poses);
        const DayPoseScore ss = score_day_poses(
            scaled_positions(common::read_tum_trajectory(dir + "/map_poses_tum.txt"), sim.scale),
            truth, sim.T_world_map, {}, o.poses);
        char scaled_row[96];
        std::snprintf(scaled_row, sizeof scaled_row, "%3d %6.3f %6.3f %6.2f %6zu\n", d, ss.rmse,
                      ss.p95, ss.max, ss.wrong);
        scaled << scaled_row;
        std::vector<Eigen::Vector3d> path;
        for (const auto& t : truth) path.push_back(t.pose.translation());

        const ObjectChanges changes = diff_objects(objects[0], objects[static_cast<size_t>(d)]);
        const std::string map_dir = dir + "/next_map";
        const bool have_map = fs::exists(map_dir) && !first_map.empty();
        MapChangeScore c;
        std::vector<Eigen::Vector3d> later;
        if (have_map) {
            later = d == 0 ? first_map
                           : map_voxel_centres(map_dir, align.T_world_map, o.min_health,
                                               o.min_planarity);
            c = score_map_changes(first_map, later, changes, unstable, o.changes);
        }
        const std::vector<ObjectAccount> accounts =
            have_map && d > 0
                ? account_left_places(first_map, start_map, later, changes,
                                      objects[static_cast<std::size_t>(d - 1)],
                                      objects[static_cast<std::size_t>(d)], path, o.changes)
                : std::vector<ObjectAccount>{};
        const AccountTotals rm_today = sum_accounts(accounts, "removed", true),
                            rm_earlier = sum_accounts(accounts, "removed", false),
                            mv_today = sum_accounts(accounts, "moved", true),
                            mv_earlier = sum_accounts(accounts, "moved", false);
        const NewGround ground = new_ground(path, earlier, later, o.ground);
        const ProcessUsage usage = read_time_report(dir + "/time.txt");
        const double map_mb = static_cast<double>(bytes_on_disk(map_dir)) / (1 << 20);
        const double maint_mb = static_cast<double>(bytes_on_disk(dir + "/maintained")) / (1 << 20);
        const double cpu_ms = usage.valid && s.scans > 0 ? 1000.0 * usage.cpu_s / s.scans : 0.0;

        char row[512];
        std::snprintf(row, sizeof row,
                      "%3d %5zu %6.1f %6.3f %6.3f %6.2f %6zu  %-16s %9s  %-13s %-11s %-12s %-12s "
                      "%-12s %-12s %4zu/%-4zu %3zu/%-3zu %7.2f %7.1f %8.1f %7.0f %6.1f\n",
                      d, s.scans, percent(s.with_pose, s.scans), s.rmse, s.p95, s.max, s.wrong,
                      kidnap_text(s).c_str(),
                      (fmt("%.0f", ground.driven) + "/" + fmt("%.0f", ground.mapped)).c_str(),
                      gone_text(c.removed_kept, c.removed_before).c_str(),
                      gone_text(c.moved_from_kept, c.moved_from_before).c_str(),
                      gone_short(rm_today).c_str(), gone_short(rm_earlier).c_str(),
                      gone_short(mv_today).c_str(), gone_short(mv_earlier).c_str(),
                      c.moved_to_present, c.moved_objects, c.added_present, c.added_objects,
                      percent(c.static_kept, c.static_before), map_mb, maint_mb,
                      usage.valid ? usage.max_rss_mb : 0.0, cpu_ms);
        table << row;
        if (!have_map) table << "    (no " << map_dir << ": map columns not scored)\n";

        report.section("day" + std::to_string(d));
        report.add_count("scans", s.scans);
        report.add_count("scans_with_map_pose", s.with_pose);
        report.add("map_pose_fraction", s.scans ? double(s.with_pose) / s.scans : 0.0);
        report.add("rmse", s.rmse, "m");
        report.add("p95", s.p95, "m");
        report.add("max", s.max, "m");
        report.add_count("poses_over_wrong", s.wrong);
        report.add("rmse_scaled", ss.rmse, "m");
        report.add("p95_scaled", ss.p95, "m");
        report.add("max_scaled", ss.max, "m");
        for (std::size_t k = 0; k < s.kidnaps.size(); ++k) {
            const std::string key = "kidnap" + std::to_string(k);
            report.add(key + "_stamp", s.kidnaps[k].stamp, "s");
            report.add(key + "_time_to_correct", s.kidnaps[k].recovered ? s.kidnaps[k].time_s : -1,
                       "s");
            report.add_count(key + "_wrong_before", s.kidnaps[k].wrong);
        }
        report.add("new_ground", ground.driven, "m");
        report.add("new_ground_mapped", ground.mapped, "m");
        report.add_count("removed_voxels_day0_map", c.removed_before);
        report.add_count("removed_voxels_kept", c.removed_kept);
        report.add_count("moved_old_voxels_day0_map", c.moved_from_before);
        report.add_count("moved_old_voxels_kept", c.moved_from_kept);
        report.add_count("moved_objects", c.moved_objects);
        report.add_count("moved_new_place_present", c.moved_to_present);
        report.add_count("moved_new_place_voxels", c.moved_to_voxels);
        report.add_count("added_objects", c.added_objects);
        report.add_count("added_present", c.added_present);
        report.add_count("added_voxels", c.added_voxels);
        for (const auto& [key, t] :
             {std::pair<const char*, AccountTotals>{"removed_today", rm_today},
              {"removed_earlier", rm_earlier},
              {"moved_today", mv_today},
              {"moved_earlier", mv_earlier}}) {
            report.add_count(std::string(key) + "_objects", t.objects);
            report.add_count(std::string(key) + "_voxels", t.before);
            report.add_count(std::string(key) + "_voxels_kept", t.kept);
        }
        report.add_count("static_voxels_day0_map", c.static_before);
        report.add_count("static_voxels_kept", c.static_kept);
        report.add("map_on_disk", map_mb, "MiB");
        report.add("maintained_on_disk", maint_mb, "MiB");
        if (usage.valid) {
            report.add("peak_memory", usage.max_rss_mb, "MiB");
            report.add("cpu_per_scan", cpu_ms, "ms");
        }

        if (!o.out.empty()) {
            LifelongDayFigure fig;
            fig.title = "day " + std::to_string(d) + ": map poses by error (one alignment, day 0)";
            fig.earlier_paths = earlier;
            for (const auto& t : truth) fig.truth.push_back(t.pose);
            fig.aligned = s.aligned;
            fig.error = s.error;
            fig.wrong = o.poses.wrong;
            fig.changes = changes;
            write_text_file(o.out + "/day" + std::to_string(d) + ".svg", lifelong_day_svg(fig));
            std::ostringstream scans;
            scans << "# stamp true_x true_y error_m (-1: no map pose) error_along error_across "
                     "error_z [m] error_yaw [deg] (the pose minus the truth: along and across "
                     "the true heading, up; yaw)\n";
            for (std::size_t i = 0; i < truth.size(); ++i) {
                const Eigen::Isometry3d& T = truth[i].pose;
                Eigen::Vector3d e = Eigen::Vector3d::Zero();
                double yaw = 0.0;
                if (s.error[i] >= 0.0) {
                    const Eigen::Vector3d dw = s.aligned[i].translation() - T.translation();
                    const Eigen::Vector3d fwd = T.linear().col(0);
                    const Eigen::Vector3d left = Eigen::Vector3d::UnitZ().cross(fwd).normalized();
                    e = {dw.dot(fwd), dw.dot(left), dw.z()};
                    const Eigen::Matrix3d dR = T.linear().transpose() * s.aligned[i].linear();
                    yaw = std::atan2(dR(1, 0), dR(0, 0)) * 180.0 / M_PI;
                }
                char line[160];
                std::snprintf(line, sizeof line, "%.3f %.2f %.2f %.3f %.3f %.3f %.3f %.3f\n",
                              truth[i].stamp, T.translation().x(), T.translation().y(), s.error[i],
                              e.x(), e.y(), e.z(), yaw);
                scans << line;
            }
            write_text_file(o.out + "/day" + std::to_string(d) + "_scans.txt", scans.str());
            if (!c.static_lost.empty()) {
                common::PlyCloud lost;
                for (const auto& p : c.static_lost) lost.points.push_back(p.cast<float>());
                common::write_ply(o.out + "/day" + std::to_string(d) + "_static_lost.ply", lost);
            }
            if (!accounts.empty()) {
                write_text_file(o.out + "/day" + std::to_string(d) + "_objects.txt",
                                objects_text(accounts));
                write_text_file(o.out + "/day" + std::to_string(d) + "_kept.txt",
                                kept_text(changes, objects[static_cast<std::size_t>(d)], first_map,
                                          later, align.T_world_map, o.changes));
            }
        }
        // Every few scans is plenty for "more than 10 m from every earlier path".
        for (std::size_t i = 0; i < path.size(); i += 5) earlier.push_back(path[i]);
        start_map = std::move(later);
    }
    table << scaled.str();
    table << "pose%: scans with a published map pose; kidnap->correct: scan time to the first "
             "pose within "
          << fmt("%.2g", o.poses.wrong)
          << " m (Nw: wrong poses before it); new/mapped: metres of new ground, and of it with "
             "voxels "
             "of the map after the day within "
          << fmt("%.2g", o.ground.map_radius)
          << " m; removed_gone / moved_gone: voxels of removed "
             "objects / moved objects' old places in day 0's map that the map after the day no "
             "longer has; moved_new / added: objects with >= "
          << o.changes.min_voxels << " voxels in the map after the day; static%: day 0's other "
          << "voxels kept; rm_today / rm_earlier / mv_today / mv_earlier: the same, objects that "
             "left today (they stood there the day before) and on an earlier day, without voxels "
             "in the box of an object standing on the day (dayN_objects.txt: object by object)\n";
    std::cout << table.str();
    if (!o.out.empty()) {
        report.write(o.out);
        write_text_file(o.out + "/table.txt", table.str());
    }
    return 0;
}

}  // namespace

Run add_lifelong(CLI::App& parent) {
    CLI::App* app = parent.add_subcommand(
        "lifelong",
        "a lifelong run day by day: map poses, kidnaps, new ground, changes, resources");
    auto o = std::make_shared<LifelongOptions>();
    app->footer(
        "RUN/dayN/ holds: map_poses_tum.txt (the map poses published online), truth/ (ltm_sim "
        "--truth-only of the day's session), slam_tum.txt (day 0: the final SLAM keyframes, for "
        "the one alignment), next_map (the map the next day localises on), maintained (the "
        "maintained state), time.txt (/usr/bin/time -v of the host).");
    app->add_option("--run", o->run, "the benchmark run's folder (day0, day1, ...)")->required();
    app->add_option("--days", o->days, "days to score")
        ->required()
        ->check(common::cli::at_least(1));
    app->add_option("--max-dt", o->poses.max_dt, "stamp pairing tolerance [s]");
    app->add_option("--wrong", o->poses.wrong, "a pose farther than this is wrong [m]");
    app->add_option("--new-ground-radius", o->ground.radius,
                    "truth path farther than this from every earlier day's is new [m]");
    app->add_option("--mapped-radius", o->ground.map_radius,
                    "new ground with a map voxel this near (3D) is mapped [m]");
    app->add_option("--box-margin", o->changes.box_margin, "object boxes grown by this [m]");
    app->add_option("--min-planarity", o->min_planarity,
                    "map voxels counted (localisation's filter) [0..1]");
    app->add_option("--min-health", o->min_health, "map voxels counted [0..1]");
    app->add_option(
        "--out", o->out,
        "write metrics.txt, metrics.json, table.txt, dayN.svg, dayN_scans.txt (each "
        "scan's error), dayN_objects.txt (each changed object's place) and "
        "dayN_kept.txt (the voxels kept in those places) and dayN_static_lost.ply (day 0's static "
        "voxels the map after the day lost) here");
    return [o] { return run_lifelong(*o); };
}

}  // namespace ltm::eval::cli
