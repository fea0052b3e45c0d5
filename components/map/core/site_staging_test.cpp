// Whose SITE/next is (site_staging.hpp): the components of one session share one claim and keep
// what any of them saved (the mapping's first save before the site component's claim); a staging
// of an earlier session (killed, cut short, unmarked, or of an earlier host in this process) is
// removed by the next session's first claim; another live session is refused and its staging left
// alone; a staging whose marker is not the session's is never committed by it.
#include "map/core/site_staging.hpp"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "common/core/io_error.hpp"
#include "map/core/map_store.hpp"
#include "map/core/site_check.hpp"
#include "map/core/site_store.hpp"
#include "map/core/site_test_maps.hpp"

namespace ltm::map {
namespace {

namespace fs = std::filesystem;

fs::path fresh_site(const std::string& name) {
    const fs::path p = fs::path(LTM_BINARY_DIR) / "site_test" / name;
    fs::remove_all(p);
    return p;
}

// A site with v0001, made as a session does (claimed, staged, committed).
SiteStore site_with_a_version(const fs::path& dir) {
    SiteStore site(dir.string());
    const auto claim = claim_staging(dir.string());
    save_map(site.staging_map_dir(), test::tiny_map(2));
    test::write_maintained_map(site.staging_maintained_map_file(), 1);
    site.commit(measure_version(site.staging_map_dir(), "", ""), 10);
    return site;
}

std::string claim_error(const std::string& site) {
    try {
        claim_staging(site);
    } catch (const common::IoError& e) {
        return e.what();
    }
    return "(claimed)";
}

// Runs `body` in a child that claims the site first, tells the parent when `body` is done and
// then waits to be killed. Returns the child's pid.
template <class Body>
pid_t child_session(const std::string& site, Body body) {
    int ready[2];
    if (pipe(ready) != 0) return -1;
    const pid_t child = fork();
    if (child != 0) {
        close(ready[1]);
        char byte = 0;
        const bool ok = read(ready[0], &byte, 1) == 1;
        close(ready[0]);
        return ok ? child : -1;
    }
    close(ready[0]);
    const auto claim = claim_staging(site);
    body();
    if (write(ready[1], "x", 1) != 1) _exit(1);
    for (;;) pause();
}

void kill_child(pid_t child) {
    ASSERT_GT(child, 0);
    ASSERT_EQ(kill(child, SIGKILL), 0);
    int status = 0;
    ASSERT_EQ(waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFSIGNALED(status));
}

// A composed host: the mapping claims and saves into the staging at its construction; the site
// component, constructed last, claims the same staging and keeps it (the old rule, "a staging
// that exists is stale", removed the mapping's save here); the commit holds it, without marker.
TEST(StagingClaim, TheComponentsOfOneSessionShareTheClaimAndKeepWhatTheFirstSaved) {
    const fs::path dir = fresh_site("staging_share");
    SiteStore site = site_with_a_version(dir);
    bool made = false;
    const auto mapping = claim_staging(dir.string(), &made);
    EXPECT_TRUE(made);
    EXPECT_EQ(mapping->removed(), "");  // the last session committed: nothing to remove
    EXPECT_EQ(mapping->staging_problem(), "");
    SaveOptions options;
    options.link_from = site.start_version("")->map_dir();
    save_map(site.staging_map_dir(), test::tiny_map(3), options);  // the mapping's first save
    const auto maintenance = claim_staging(dir.string(), &made);
    EXPECT_FALSE(made);
    const auto site_component = claim_staging((dir / "." / "").string(), &made);  // same site
    EXPECT_FALSE(made);
    EXPECT_EQ(site_component.get(), mapping.get());
    EXPECT_EQ(maintenance.get(), mapping.get());
    EXPECT_EQ(check_map_dir(site.staging_map_dir()), "");  // the first save is still whole
    EXPECT_EQ(read_staging_mark(dir.string()).id, mapping->mark().id);
    EXPECT_EQ(read_staging_mark(dir.string()).pid, long(getpid()));

    // A version on request: the snapshot holds no marker.
    const std::string snapshot = site.snapshot_staging();
    EXPECT_FALSE(fs::exists(fs::path(snapshot) / "session"));
    fs::remove_all(snapshot);

    test::write_maintained_map(site.staging_maintained_map_file(), 2);
    EXPECT_EQ(site_component->staging_problem(), "");
    const SiteVersion v2 = site.commit(
        measure_version(site.staging_map_dir(), site.start_version("")->map_dir(), "v0001"), 10);
    EXPECT_EQ(v2.name, "v0002");
    EXPECT_EQ(load_map(v2.map_dir()).map.local_maps.size(), 3u);
    EXPECT_FALSE(fs::exists(fs::path(v2.dir) / "session"));  // a version holds no marker
    EXPECT_FALSE(fs::exists(site.staging_dir()));
    EXPECT_NE(site_component->staging_problem().find("is gone"), std::string::npos);
}

// A session killed (SIGKILL) after it claimed and saved: the next session's first claim removes
// its staging and says whose it was; so does a staging without a marker (cut short before the
// marker was written, or left by a build without markers).
TEST(StagingClaim, AStagingOfAnEarlierSessionIsRemovedAndSaysWhoseItWas) {
    const fs::path dir = fresh_site("staging_earlier");
    SiteStore site = site_with_a_version(dir);
    const pid_t child = child_session(dir.string(), [&] {
        save_map(site.staging_map_dir(), test::tiny_map(4));
        test::write_maintained_map(site.staging_maintained_map_file(), 3);
    });
    const StagingMark theirs = read_staging_mark(dir.string());
    EXPECT_EQ(theirs.pid, long(child));
    kill_child(child);
    {
        const auto claim = claim_staging(dir.string());
        EXPECT_NE(claim->removed().find("removed " + site.staging_dir() +
                                        ": the staging of a session that did not finish (pid " +
                                        std::to_string(child) + ", claimed "),
                  std::string::npos)
            << claim->removed();
        EXPECT_NE(claim->mark().id, theirs.id);
        EXPECT_FALSE(fs::exists(site.staging_map_dir()));  // none of the dead session's files
        EXPECT_FALSE(fs::exists(site.staging_maintained_map_file()));
        EXPECT_EQ(read_staging_mark(dir.string()).id, claim->mark().id);
    }
    // Unmarked.
    fs::remove_all(site.staging_dir());
    save_map(site.staging_map_dir(), test::tiny_map(3));
    const auto claim = claim_staging(dir.string());
    EXPECT_NE(claim->removed().find("did not finish (unmarked)"), std::string::npos)
        << claim->removed();
    EXPECT_FALSE(fs::exists(site.staging_map_dir()));
    EXPECT_EQ(site.versions().size(), 1u);  // no version made or lost
}

// Another live session holds the site: a claim is refused in one line naming its pid, and its
// staging stays as it is (before, a second host's mapping saved into it before its site component
// was refused).
TEST(StagingClaim, AnotherLiveSessionIsRefusedAndItsStagingIsLeftAlone) {
    const fs::path dir = fresh_site("staging_live");
    SiteStore site = site_with_a_version(dir);
    const pid_t child =
        child_session(dir.string(), [&] { save_map(site.staging_map_dir(), test::tiny_map(4)); });
    ASSERT_GT(child, 0);
    const StagingMark theirs = read_staging_mark(dir.string());
    const std::string error = claim_error(dir.string());
    EXPECT_NE(error.find("in use by pid " + std::to_string(child)), std::string::npos) << error;
    EXPECT_EQ(error.find('\n'), std::string::npos);
    EXPECT_EQ(read_staging_mark(dir.string()).id, theirs.id);
    EXPECT_EQ(check_map_dir(site.staging_map_dir()), "");
    kill_child(child);
}

// A host of this process that ended without committing, then another one on the same site (as
// tests and tools do): the second is a new session, the first one's staging is removed.
TEST(StagingClaim, ALaterSessionInTheSameProcessIsANewOne) {
    const fs::path dir = fresh_site("staging_again");
    SiteStore site = site_with_a_version(dir);
    std::string first;
    {
        const auto claim = claim_staging(dir.string());
        first = claim->mark().id;
        save_map(site.staging_map_dir(), test::tiny_map(3));
    }
    const auto claim = claim_staging(dir.string());
    EXPECT_NE(claim->mark().id, first);
    EXPECT_NE(claim->removed().find("pid " + std::to_string(getpid())), std::string::npos)
        << claim->removed();
    EXPECT_FALSE(fs::exists(site.staging_map_dir()));
}

// A marker replaced behind the session's back (by hand, or a process that ignored the lock): the
// staging is not this session's and says so.
TEST(StagingClaim, AStagingMarkedByAnotherSessionIsNotThisOnes) {
    const fs::path dir = fresh_site("staging_replaced");
    SiteStore site = site_with_a_version(dir);
    const auto claim = claim_staging(dir.string());
    std::ofstream(site.staging_marker_file())
        << "ltm site staging\nsession other\npid 1\nclaimed 2026-01-01 00:00:00 UTC\n";
    const std::string problem = claim->staging_problem();
    EXPECT_NE(problem.find("is not this session's (its marker: pid 1, claimed 2026-01-01"),
              std::string::npos)
        << problem;
    EXPECT_EQ(problem.find('\n'), std::string::npos);
}

}  // namespace
}  // namespace ltm::map
