// ltm_site: a site's map versions (map/core/site_store.hpp), for `./ltm map versions|check SITE`.
//   versions SITE                 every version: number, date, intact or what is damaged, and
//                                 what its session changed, one line each
//   check SITE [--version V]      the version a session would start from (and the damaged ones
//                                 it would skip); exit 1 when a named version is unknown or
//                                 damaged, as a session would refuse it
#include <cstdio>
#include <string>

#include "common/cli/cli.hpp"
#include "common/core/file_io.hpp"
#include "common/core/io_error.hpp"
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
    if (const int code = ltm::common::cli::parse(app, argc, argv); code >= 0) return code;
    try {
        if (versions->parsed()) return list_versions(site);
        return check(site, version);
    } catch (const ltm::common::IoError& e) {
        std::fprintf(stderr, "ltm_site: %s\n", e.what());
        return 1;
    }
}
