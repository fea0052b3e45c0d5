#pragma once
// A site's folder: the versions of its map, one a session, and the staging of the running one.
//   SITE/versions/v0001/map/                            a map directory (map_store.hpp)
//   SITE/versions/v0001/maintenance/long_term_map.bin   the maintained map (maintenance core)
//   SITE/versions/v0001/version.txt                     what the session changed (version_summary)
//   SITE/next/                     the running session's staging: next/map/, next/maintenance/...,
//                                  next/session (whose it is: site_staging.hpp)
//   SITE/lock                      held by the host running a session (site_lock.hpp)
// A session starts from a version (named, or the newest intact one), saves into SITE/next (the
// mapping with SaveOptions::link_from = the start version's map: unchanged files are hard links,
// not copies) and at its end commit() makes the staging the next version by one rename. A crash
// or a full disk before that rename leaves every version as it was; SITE/next is then an earlier
// session's, and the next session's first claim removes it (site_staging.hpp: writers claim the
// staging under the site's lock before they write; a staging is never removed by its own session).
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "map/core/version_summary.hpp"

namespace ltm::map {

struct SiteVersion {
    std::uint32_t number = 0;  // 1, 2, ...
    std::string name;          // "v0003"
    std::string dir;           // SITE/versions/v0003
    // The map's manifest and every file it names check out (sizes, hashes: no voxel decoded) and
    // the maintained map's sections (when there is one): site_check.hpp.
    bool intact = false;
    std::string problem;  // one line when not intact
    std::string map_dir() const { return dir + "/map"; }
    std::string maintained_map_file() const { return dir + "/maintenance/long_term_map.bin"; }
    std::string summary_file() const { return dir + "/version.txt"; }
};

// "v0003" of 3.
std::string version_name(std::uint32_t number);
// The number of a version folder's name ("v0003" -> 3), 0 when it is not one.
std::uint32_t version_number(const std::string& folder_name);

class SiteStore {
  public:
    explicit SiteStore(std::string site_dir);  // does not create anything
    const std::string& dir() const { return dir_; }

    // Every version, ascending, each checked (reads every file once).
    std::vector<SiteVersion> versions() const;
    // The version a session starts from. `name` given ("v0003" or "3"): that version, or throws
    // common::IoError with one line (unknown: lists the known ones; damaged: says what). Empty:
    // the newest intact one; each newer damaged one skipped is described in *notes ("v0005 is
    // damaged (...): starting on v0004"); nullopt when the site has no intact version (a new
    // site).
    std::optional<SiteVersion> start_version(const std::string& name,
                                             std::vector<std::string>* notes = nullptr) const;

    std::string staging_dir() const;  // SITE/next
    std::string staging_map_dir() const;
    std::string staging_maintained_map_file() const;
    std::string lock_file() const;  // SITE/lock
    // SITE/next/session: whose staging it is (site_staging.hpp; removed by commit before its
    // rename, so a version holds no marker).
    std::string staging_marker_file() const;

    // "" when the staging holds a whole map (and a whole maintained map, if any), else one line.
    std::string staging_problem() const;

    // Makes the staged session the next version atomically (version.txt written into the
    // staging, fsync, rename SITE/next -> SITE/versions/vNNNN, fsync of SITE/versions), then
    // removes the oldest versions beyond `keep` (at least 1; never the one just made, never
    // `summary.started_from` while it is the only intact version older than the new one).
    // Staging without a maintained map takes the start version's (hard-linked: a session without
    // maintenance keeps what earlier ones learnt). Throws common::IoError (one line) when the
    // staging is missing or not intact; nothing changes then. Sets number and created.
    SiteVersion commit(VersionSummary summary, std::size_t keep);
    // A version on request in the middle of a session (issue 26): the staging as it is now,
    // hard-linked file by file into SITE/.snapshot (every map file is written to a temporary name
    // and renamed, never changed in place, so the links keep what the staging held; the staging
    // goes on). Returns that folder; measure it, then commit_snapshot(). Throws common::IoError.
    std::string snapshot_staging() const;
    // Makes a snapshot the next version as adopt() does (checked whole first: a save that ran
    // during the snapshot fails the check and nothing changes; take another snapshot), with
    // version.txt from `summary` and the start version's maintained map when none was staged.
    SiteVersion commit_snapshot(const std::string& snapshot, VersionSummary summary,
                                std::size_t keep);
    // A version made elsewhere and received whole (the base station's, site_sync): the folder
    // `made_dir` (on this site's filesystem, holding map/ and maybe maintenance/ and version.txt)
    // is checked, fsynced and renamed to SITE/versions/v<number> in one rename, then pruned as by
    // commit(). Throws common::IoError (one line) when the folder is not whole or the site has a
    // version of that number already; nothing changes then.
    SiteVersion adopt(const std::string& made_dir, std::uint32_t number, std::size_t keep);
    // The versions commit() or adopt() removed (names), for the log.
    const std::vector<std::string>& pruned() const { return pruned_; }

  private:
    void prune(const SiteVersion& made, const std::string& started_from, std::size_t keep);
    SiteVersion adopt_as(const std::string& made_dir, std::uint32_t number, std::size_t keep,
                         const std::string& started_from);
    std::string dir_;
    std::vector<std::string> pruned_;
};

// What a component needs to take part in a session on a site: the start version (or none: a new
// site), the notes on damaged versions skipped, and where to save. Throws common::IoError (one
// line) for a named version that is unknown or damaged.
struct SiteSession {
    std::string site_dir;
    std::optional<SiteVersion> start;
    std::vector<std::string> notes;
    std::string staging_dir, staging_map_dir, staging_maintained_map_file;
    // "v0004 (SITE/versions/v0004)" or "none (a new site)".
    std::string describe() const;
};
SiteSession resolve_site(const std::string& site_dir, const std::string& version_name);

}  // namespace ltm::map
