// ltm_site: a site's map versions (map/core/site_store.hpp), for `./ltm map versions|check SITE`.
//   versions SITE                 every version: number, date, intact or what is damaged, and
//                                 what its session changed, one line each
//   check SITE [--version V]      the version a session would start from (and the damaged ones
//                                 it would skip); exit 1 when a named version is unknown or
//                                 damaged, as a session would refuse it
//   import SITE --map DIR [--maintained FILE] [--keep N]
//                                 a saved map (a robot_maintain.yaml run's, say) made the site's
//                                 next version, as a session would: loaded and checked, saved
//                                 into the staging with its files hard-linked where they can be,
//                                 committed
//   anchor SITE (--points FILE | --transform X Y Z ROLL PITCH YAW)
//                                 SITE/anchor.yaml: the site's own frame against the map's,
//                                 given (metres, degrees) or fitted to surveyed points (map xyz
//                                 site xyz a line, at least 3: Umeyama without scale)
#include <Eigen/Geometry>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "common/cli/cli.hpp"
#include "common/core/file_io.hpp"
#include "common/core/io_error.hpp"
#include "map/core/map_store.hpp"
#include "map/core/site_anchor.hpp"
#include "map/core/site_staging.hpp"
#include "map/core/site_store.hpp"

namespace {

using ltm::map::SiteStore;
using ltm::map::SiteVersion;

std::string summary_of(const SiteVersion& v, std::string* date) {
    try {
        const ltm::map::VersionSummary s = ltm::map::parse_version_text(
            ltm::common::read_file(v.summary_file(), "version.txt"), "version.txt");
        *date = ltm::map::version_date(s.created);
        return ltm::map::version_line(s);
    } catch (const ltm::common::IoError& e) {
        *date = "(no date)";
        return e.what();
    }
}

int list_versions(const std::string& dir) {
    const SiteStore site(dir);
    const std::vector<SiteVersion> all = site.versions();
    if (all.empty()) {
        std::printf("site %s: no versions (a new site)\n", dir.c_str());
        return 0;
    }
    std::printf("site %s: %zu versions\n", dir.c_str(), all.size());
    for (const SiteVersion& v : all) {
        std::string date;
        const std::string summary = summary_of(v, &date);
        std::printf("%s  %s  %s  %s\n", v.name.c_str(), date.c_str(),
                    v.intact ? "intact " : "DAMAGED", summary.c_str());
        if (!v.intact) std::printf("       damaged: %s\n", v.problem.c_str());
    }
    return 0;
}

int check(const std::string& dir, const std::string& version) {
    std::vector<std::string> notes;
    const SiteStore site(dir);
    const auto start = site.start_version(version, &notes);  // throws: refused
    for (const std::string& n : notes) std::printf("%s\n", n.c_str());
    if (start)
        std::printf("a session starts from %s (%s)\n", start->name.c_str(), start->dir.c_str());
    else
        std::printf("a session starts as a new site (no intact version)\n");
    return 0;
}

int import_map(const std::string& dir, const std::string& map_dir, const std::string& maintained,
               std::size_t keep) {
    const auto claim = ltm::map::claim_staging(dir);  // the site's lock; an earlier staging gone
    if (!claim->removed().empty()) std::printf("%s\n", claim->removed().c_str());
    SiteStore site(dir);
    std::vector<std::string> notes;
    const auto start = site.start_version("", &notes);
    for (const std::string& n : notes) std::printf("%s\n", n.c_str());
    const auto t0 = std::chrono::steady_clock::now();
    const ltm::map::LoadedMap loaded = ltm::map::load_map(map_dir);
    if (!loaded.refused.empty())
        throw ltm::common::IoError(map_dir, "not whole: " + loaded.refused.front());
    ltm::map::SaveOptions options;
    options.link_from = map_dir;
    const ltm::map::SaveStats stats =
        ltm::map::save_map(site.staging_map_dir(), loaded.map, options);
    if (!maintained.empty()) {
        std::error_code ec;
        std::filesystem::create_directories(
            std::filesystem::path(site.staging_maintained_map_file()).parent_path());
        std::filesystem::create_hard_link(maintained, site.staging_maintained_map_file(), ec);
        if (ec) std::filesystem::copy_file(maintained, site.staging_maintained_map_file());
    }
    ltm::map::VersionSummary summary = ltm::map::measure_version(
        site.staging_map_dir(), start ? start->map_dir() : "", start ? start->name : "");
    const SiteVersion made = site.commit(summary, keep);
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("%s: %s\n", made.dir.c_str(), ltm::map::version_line(summary).c_str());
    std::printf("files: %zu written, %zu hard-linked, %zu kept; %.1f MiB in the map; %.2f s\n",
                stats.files_written, stats.files_linked, stats.files_kept,
                stats.bytes_total / 1048576.0, s);
    for (const std::string& name : site.pruned()) std::printf("removed %s\n", name.c_str());
    return 0;
}

int anchor(const std::string& dir, const std::string& points, const std::vector<double>& t) {
    ltm::map::SiteAnchor a;
    if (!points.empty()) {
        std::vector<Eigen::Vector3d> map_xyz, site_xyz;
        ltm::map::read_survey_points(points, &map_xyz, &site_xyz);
        a = ltm::map::fit_anchor(map_xyz, site_xyz);
    } else {
        a = ltm::map::anchor_from_transform({t[0], t[1], t[2]}, t[3], t[4], t[5]);
    }
    ltm::map::write_anchor(dir, a);
    const Eigen::Vector3d x = a.T_site_map.translation();
    const double yaw = std::atan2(a.T_site_map(1, 0), a.T_site_map(0, 0)) * 180.0 / M_PI;
    std::printf("%s: translation %.3f %.3f %.3f m, yaw %.3f deg",
                ltm::map::anchor_file(dir).c_str(), x.x(), x.y(), x.z(), yaw);
    if (a.source == "points")
        std::printf("; fitted to %zu points: residuals rms %.4f m, max %.4f m", a.points, a.rms_m,
                    a.max_m);
    std::printf("\n");
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"A site's map versions: list them, or check which one a session starts from",
                 "ltm_site"};
    ltm::common::cli::configure(app);
    app.require_subcommand(1);
    std::string site, version;
    CLI::App* versions =
        app.add_subcommand("versions", "every version with what its session changed");
    versions->add_option("SITE", site, "the site's folder")->required();
    CLI::App* check_cmd = app.add_subcommand("check", "the version a session would start from");
    check_cmd->add_option("SITE", site, "the site's folder")->required();
    check_cmd->add_option("--version", version, "a named version (v0003 or 3)");
    CLI::App* import_cmd = app.add_subcommand("import", "a saved map made the next version");
    std::string map_dir, maintained;
    int keep = 10;
    import_cmd->add_option("SITE", site, "the site's folder (created when missing)")->required();
    import_cmd->add_option("--map", map_dir, "the saved map directory")->required();
    import_cmd->add_option("--maintained", maintained, "its maintained map (long_term_map.bin)");
    import_cmd->add_option("--keep", keep, "versions kept")->check(ltm::common::cli::at_least(1));
    CLI::App* anchor_cmd = app.add_subcommand("anchor", "the site's own frame against the map's");
    std::string points;
    std::vector<double> transform;
    anchor_cmd->add_option("SITE", site, "the site's folder")->required();
    auto* points_opt = anchor_cmd->add_option(
        "--points", points, "surveyed points: map x y z site x y z a line (at least 3)");
    auto* transform_opt = anchor_cmd
                              ->add_option("--transform", transform,
                                           "p_site = T p_map: x y z [m] roll pitch yaw [deg]")
                              ->expected(6);
    points_opt->excludes(transform_opt);
    if (const int code = ltm::common::cli::parse(app, argc, argv); code >= 0) return code;
    try {
        if (versions->parsed()) return list_versions(site);
        if (import_cmd->parsed()) return import_map(site, map_dir, maintained, std::size_t(keep));
        if (anchor_cmd->parsed()) {
            if (points.empty() && transform.empty())
                return ltm::common::cli::usage_error(
                    app, ltm::common::cli::UsageError(
                             "give --points FILE or --transform X Y Z ROLL PITCH YAW"));
            return anchor(site, points, transform);
        }
        return check(site, version);
    } catch (const std::exception& e) {  // one line: IoError, a filesystem error
        std::fprintf(stderr, "ltm_site: %s\n", e.what());
        return 1;
    }
}
