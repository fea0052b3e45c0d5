#pragma once
// Whose SITE/next is (issue 26, item 3): the staging of a site belongs to the session that claimed
// it, and only a staging of another session is removed.
//
// Every writer into a site's staging (the mapping and the maintenance with `site_dir`, the `site`
// component that commits it, `ltm_site import`) claims it before its first write: the first claim
// of a process takes the site's lock (site_lock.hpp) and then makes the staging this session's:
//   - SITE/next marked as this session's (SITE/next/session names it): kept as it is;
//   - SITE/next of another session (its marker names another one: a session that crashed, was
//     killed or could not commit) or unmarked (cut short before its marker was written, or made
//     by a build without markers): removed, one line says whose it was;
//   then SITE/next is made (when missing) and marked, before anything is written into it.
// Later claims in the same process (the other components of a composed host) share that claim:
// the lock, and the staging, which they keep whatever it holds (the mapping's first save at its
// construction, before the site component is constructed). The lock goes with the last claim.
//
// Why: the site component is constructed last (it stops last, to commit what the others saved)
// and removed SITE/next whenever it existed ("stale = exists"), while a composed host's mapping
// had already saved into it at its own construction; a lifelong day lost its version so when the
// mapping paged local maps out onto the files removed (site_week day 4, session 23). And the
// mapping wrote into SITE/next before the lock was taken: a second host started on a running
// site saved into that session's staging before its site component refused it. Claimed under the
// lock before any write, a staging only ever holds one session's files, so a version is never
// committed from a mix of two sessions (SiteStore::commit removes the marker before its rename).
#include <memory>
#include <string>

namespace ltm::map {

class SiteLock;

// What a marker says: the session's id (unique: process, start time and a random part) and, for
// people, the pid and the time of the claim.
struct StagingMark {
    std::string id;
    long pid = 0;
    std::string claimed;  // "2026-11-29 12:34:56 UTC"
    // "pid 4242, claimed 2026-11-29 12:34:56 UTC" (or "unmarked").
    std::string describe() const;
};
// The marker of SITE/next (SiteStore::staging_marker_file), or an empty mark (id "") when there is
// none or it cannot be read.
StagingMark read_staging_mark(const std::string& site_dir);

class StagingClaim {
  public:
    explicit StagingClaim(const std::string& site_dir);  // use claim_staging()
    ~StagingClaim();
    StagingClaim(const StagingClaim&) = delete;
    StagingClaim& operator=(const StagingClaim&) = delete;

    const std::string& site_dir() const { return site_dir_; }
    const StagingMark& mark() const { return mark_; }
    // One line when this claim removed another session's staging ("" when there was none):
    // "removed SITE/next: the staging of a session that did not finish (pid 4242, claimed ...)".
    const std::string& removed() const { return removed_; }
    // "" when SITE/next is there and marked as this session's; else one line why not.
    std::string staging_problem() const;

  private:
    std::string site_dir_;
    std::unique_ptr<SiteLock> lock_;
    StagingMark mark_;
    std::string removed_;
};

// The claim of this process on the site's staging (see above): the existing one when a component
// of this process holds it (*made = false), else a new one (*made = true). Throws common::IoError
// with one line when another process holds the site ("SITE/lock: the site is in use by pid 4242
// ..."), or the staging cannot be removed or marked.
std::shared_ptr<StagingClaim> claim_staging(const std::string& site_dir, bool* made = nullptr);

}  // namespace ltm::map
