#include "map/core/site_store.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>

#include "common/core/file_io.hpp"
#include "common/core/io_error.hpp"
#include "map/core/site_check.hpp"

namespace ltm::map {
namespace {

namespace fs = std::filesystem;

constexpr const char* kVersions = "versions";
constexpr const char* kStaging = "next";
constexpr const char* kMaintained = "maintenance/long_term_map.bin";
constexpr const char* kRemoving = ".removing-";
constexpr const char* kMarker = "session";  // SITE/next/session (site_staging.hpp)

// A version named by the user: "v0003", "v3" or "3".
std::uint32_t parse_user_name(const std::string& name) {
    if (!name.empty() && name[0] != 'v') return version_number("v" + name);
    return version_number(name);
}

// Every version folder, ascending, not checked.
std::vector<SiteVersion> list(const std::string& site) {
    std::vector<SiteVersion> out;
    std::error_code ec;
    const fs::path root = fs::path(site) / kVersions;
    for (const fs::directory_entry& e : fs::directory_iterator(root, ec)) {
        const std::string name = e.path().filename().string();
        const std::uint32_t n = version_number(name);
        if (n == 0 || !e.is_directory(ec)) continue;
        SiteVersion v;
        v.number = n;
        v.name = name;
        v.dir = (root / name).string();
        out.push_back(v);
    }
    std::sort(out.begin(), out.end(),
              [](const SiteVersion& a, const SiteVersion& b) { return a.number < b.number; });
    return out;
}

void check(SiteVersion& v) {
    v.problem = check_map_dir(v.map_dir());
    if (v.problem.empty()) v.problem = check_maintained_map_file(v.maintained_map_file());
    v.intact = v.problem.empty();
}

void link_or_copy(const fs::path& from, const fs::path& to) {
    std::error_code ec;
    fs::create_directories(to.parent_path(), ec);
    fs::create_hard_link(from, to, ec);
    if (!ec) return;
    fs::copy_file(from, to, fs::copy_options::overwrite_existing, ec);
    if (ec) throw common::IoError(to.string(), "cannot carry the maintained map: " + ec.message());
}

std::string known(const std::vector<SiteVersion>& all) {
    if (all.empty()) return "the site has no versions";
    std::string s = "known: ";
    for (std::size_t i = 0; i < all.size(); ++i) s += (i ? ", " : "") + all[i].name;
    return s;
}

}  // namespace

std::uint32_t version_number(const std::string& name) {
    if (name.size() < 2 || name[0] != 'v' || name.size() > 10) return 0;
    std::uint64_t n = 0;
    for (std::size_t i = 1; i < name.size(); ++i) {
        if (name[i] < '0' || name[i] > '9') return 0;
        n = n * 10 + std::uint64_t(name[i] - '0');
    }
    return n > 0 && n <= 0xffffffffull ? std::uint32_t(n) : 0;
}

std::string version_name(std::uint32_t number) {
    char buf[16];
    std::snprintf(buf, sizeof buf, "v%04u", number);
    return buf;
}

SiteStore::SiteStore(std::string site_dir) : dir_(std::move(site_dir)) {}

std::vector<SiteVersion> SiteStore::versions() const {
    std::vector<SiteVersion> all = list(dir_);
    for (SiteVersion& v : all) check(v);
    return all;
}

std::optional<SiteVersion> SiteStore::start_version(const std::string& name,
                                                    std::vector<std::string>* notes) const {
    std::vector<SiteVersion> all = list(dir_);
    if (!name.empty()) {
        const std::uint32_t n = parse_user_name(name);
        if (n == 0)
            throw common::IoError(dir_,
                                  "version '" + name + "' is not a version name (v0003 or 3)");
        for (SiteVersion& v : all) {
            if (v.number != n) continue;
            check(v);
            if (!v.intact)
                throw common::IoError(dir_, v.name + " is damaged (" + v.problem +
                                                "): start on another version or none");
            return v;
        }
        throw common::IoError(dir_, "no version " + version_name(n) + " (" + known(all) + ")");
    }
    std::vector<const SiteVersion*> damaged;  // newer than the one found
    for (auto it = all.rbegin(); it != all.rend(); ++it) {
        check(*it);
        if (it->intact) {
            if (notes)
                for (const SiteVersion* d : damaged)
                    notes->push_back(d->name + " is damaged (" + d->problem + "): starting on " +
                                     it->name);
            return *it;
        }
        damaged.push_back(&*it);
    }
    if (notes)
        for (const SiteVersion* d : damaged)
            notes->push_back(d->name + " is damaged (" + d->problem +
                             "): no intact version, starting as a new site");
    return std::nullopt;
}

std::string SiteStore::staging_dir() const { return (fs::path(dir_) / kStaging).string(); }
std::string SiteStore::staging_map_dir() const { return staging_dir() + "/map"; }
std::string SiteStore::staging_maintained_map_file() const {
    return staging_dir() + "/" + kMaintained;
}
std::string SiteStore::lock_file() const { return (fs::path(dir_) / "lock").string(); }
std::string SiteStore::staging_marker_file() const { return staging_dir() + "/" + kMarker; }

std::string SiteStore::staging_problem() const {
    std::error_code ec;
    if (!fs::is_directory(staging_dir(), ec)) return "no staging: the session saved nothing";
    if (!fs::exists(fs::path(staging_map_dir()) / "manifest.txt", ec))
        return "no map saved in the staging (next/map/manifest.txt missing)";
    if (const std::string p = check_map_dir(staging_map_dir()); !p.empty())
        return "the session's map is not whole: " + p;
    if (const std::string p = check_maintained_map_file(staging_maintained_map_file()); !p.empty())
        return "the session's maintained map is not whole: " + p;
    return "";
}

SiteVersion SiteStore::commit(VersionSummary summary, std::size_t keep) {
    pruned_.clear();
    const fs::path staging(staging_dir());
    std::error_code ec;
    if (const std::string p = staging_problem(); !p.empty())
        throw common::IoError(staging.string(), p);

    const std::vector<SiteVersion> before = list(dir_);
    // No maintained map staged: the start version's stays with the map.
    if (!fs::exists(staging_maintained_map_file(), ec) && !summary.started_from.empty()) {
        for (const SiteVersion& v : before)
            if (v.name == summary.started_from && fs::exists(v.maintained_map_file(), ec))
                link_or_copy(v.maintained_map_file(), staging_maintained_map_file());
    }
    summary.number = before.empty() ? 1 : before.back().number + 1;
    if (summary.created == 0) summary.created = std::int64_t(std::time(nullptr));
    common::write_file_atomic((staging / "version.txt").string(), write_version_text(summary));
    // Whose staging it was is not part of the version (a crash from here on leaves an unmarked
    // staging, which the next session removes: nothing was committed).
    fs::remove(staging_marker_file(), ec);
    for (const char* sub : {"map/local_maps", "map", "maintenance", ""})
        common::sync_folder((staging / sub).string());

    const fs::path versions = fs::path(dir_) / kVersions;
    fs::create_directories(versions, ec);
    if (ec) throw common::IoError(versions.string(), "cannot create: " + ec.message());
    common::sync_folder(dir_);
    SiteVersion made;
    made.number = summary.number;
    made.name = version_name(made.number);
    made.dir = (versions / made.name).string();
    if (::rename(staging.c_str(), made.dir.c_str()) != 0)
        throw common::IoError(made.dir,
                              std::string("cannot make the version: ") + std::strerror(errno));
    common::sync_folder(versions.string());
    made.intact = true;

    prune(made, summary.started_from, keep);
    return made;
}

void SiteStore::prune(const SiteVersion& made, const std::string& started_from, std::size_t keep) {
    const fs::path versions = fs::path(dir_) / kVersions;
    std::error_code ec;
    // Pruning: the oldest beyond `keep`. Interrupted removals (".removing-v0001") first.
    for (const fs::directory_entry& e : fs::directory_iterator(versions, ec))
        if (e.path().filename().string().rfind(kRemoving, 0) == 0) fs::remove_all(e.path(), ec);
    keep = std::max<std::size_t>(keep, 1);
    std::vector<SiteVersion> all = list(dir_);
    std::size_t count = all.size();
    for (std::size_t i = 0; i < all.size() && count > keep; ++i) {
        SiteVersion& v = all[i];
        if (v.number == made.number) continue;
        if (v.name == started_from) {
            bool other_intact = false;
            for (std::size_t j = 0; j < all.size() && !other_intact; ++j) {
                if (j == i || all[j].number >= made.number) continue;
                check(all[j]);
                other_intact = all[j].intact;
            }
            if (!other_intact) continue;
        }
        const fs::path doomed = versions / (std::string(kRemoving) + v.name);
        if (::rename(v.dir.c_str(), doomed.c_str()) != 0) continue;
        fs::remove_all(doomed, ec);
        pruned_.push_back(v.name);
        --count;
    }
    common::sync_folder(versions.string());
}

SiteVersion SiteStore::adopt(const std::string& made_dir, std::uint32_t number, std::size_t keep) {
    return adopt_as(made_dir, number, keep, "");
}

SiteVersion SiteStore::adopt_as(const std::string& made_dir, std::uint32_t number, std::size_t keep,
                                const std::string& started_from) {
    pruned_.clear();
    const fs::path from(made_dir);
    if (number == 0) throw common::IoError(made_dir, "version number 0");
    if (const std::string p = check_map_dir((from / "map").string()); !p.empty())
        throw common::IoError(made_dir, "not a whole version: " + p);
    if (const std::string p = check_maintained_map_file((from / kMaintained).string()); !p.empty())
        throw common::IoError(made_dir, "not a whole version: " + p);
    SiteVersion made;
    made.number = number;
    made.name = version_name(number);
    const fs::path versions = fs::path(dir_) / kVersions;
    made.dir = (versions / made.name).string();
    std::error_code ec;
    if (fs::exists(made.dir, ec))
        throw common::IoError(made.dir, "the site has a " + made.name + " already");
    for (const char* sub : {"map/local_maps", "map", "maintenance", ""})
        common::sync_folder((from / sub).string());
    fs::create_directories(versions, ec);
    if (ec) throw common::IoError(versions.string(), "cannot create: " + ec.message());
    common::sync_folder(dir_);
    if (::rename(from.c_str(), made.dir.c_str()) != 0)
        throw common::IoError(made.dir,
                              std::string("cannot make the version: ") + std::strerror(errno));
    common::sync_folder(versions.string());
    made.intact = true;
    prune(made, started_from, keep);
    return made;
}

std::string SiteStore::snapshot_staging() const {
    const fs::path from(staging_dir());
    const fs::path to = fs::path(dir_) / ".snapshot";
    std::error_code ec;
    fs::remove_all(to, ec);
    if (!fs::is_directory(from / "map", ec))
        throw common::IoError(from.string(), "no staging map yet: the session saved nothing");
    // The manifest first: files it names may be replaced later by a save (the check catches it).
    fs::create_directories(to / "map", ec);
    fs::create_hard_link(from / "map/manifest.txt", to / "map/manifest.txt", ec);
    if (ec) throw common::IoError(from.string(), "no staged manifest: " + ec.message());
    for (fs::recursive_directory_iterator it(from, ec), end; !ec && it != end; it.increment(ec)) {
        const fs::path rel = fs::relative(it->path(), from, ec);
        const std::string name = it->path().filename().string();
        if (it->is_directory(ec)) {
            fs::create_directories(to / rel, ec);
        } else if (rel != "map/manifest.txt" && rel != kMarker &&
                   name.find(".tmp") == std::string::npos) {
            std::error_code link;
            fs::create_hard_link(it->path(), to / rel, link);  // gone meanwhile: the check says
        }
    }
    if (ec) throw common::IoError(from.string(), "cannot snapshot: " + ec.message());
    return to.string();
}

SiteVersion SiteStore::commit_snapshot(const std::string& snapshot, VersionSummary summary,
                                       std::size_t keep) {
    const fs::path snap(snapshot);
    std::error_code ec;
    const std::vector<SiteVersion> before = list(dir_);
    if (!fs::exists(snap / kMaintained, ec) && !summary.started_from.empty())
        for (const SiteVersion& v : before)
            if (v.name == summary.started_from && fs::exists(v.maintained_map_file(), ec))
                link_or_copy(v.maintained_map_file(), snap / kMaintained);
    summary.number = before.empty() ? 1 : before.back().number + 1;
    if (summary.created == 0) summary.created = std::int64_t(std::time(nullptr));
    common::write_file_atomic((snap / "version.txt").string(), write_version_text(summary));
    try {
        return adopt_as(snapshot, summary.number, keep, summary.started_from);
    } catch (const common::IoError&) {
        fs::remove_all(snap, ec);
        throw;
    }
}

std::string SiteSession::describe() const {
    return start ? start->name + " (" + start->dir + ")" : std::string("none (a new site)");
}

SiteSession resolve_site(const std::string& site_dir, const std::string& version_name) {
    SiteSession s;
    s.site_dir = site_dir;
    const SiteStore store(site_dir);
    s.start = store.start_version(version_name, &s.notes);
    s.staging_dir = store.staging_dir();
    s.staging_map_dir = store.staging_map_dir();
    s.staging_maintained_map_file = store.staging_maintained_map_file();
    return s;
}

}  // namespace ltm::map
