// The site of a lifelong session as a component (issue 26, item 3): constructed LAST in the
// launch config, so that the others (localisation, mapping, maintenance) have resolved the same
// start version (map/core/site_store.hpp: resolve_site) and stopped LAST, so that they have
// saved into the staging (SITE/next) when it commits.
//   construction: claims the site's staging (map/core/site_staging.hpp; the claim holds
//     SITE/lock: another live session is a one-line error, the host refuses to start), checks that
//     every component with a `site_dir` names this site and version, and says which version the
//     session starts from (and which damaged ones it skipped). The mapping and the maintenance
//     claimed the staging before it (constructed earlier, the mapping may have saved into it
//     already): the claim is theirs, shared, and the staging is kept; the first claim of the
//     session removed a staging an earlier session left (crashed, killed, not committed);
//   map_changes (ltm_msgs/MapChangeSet, the maintenance's): voxels removed and added, summed for
//     the version's summary;
//   shutdown: the staging checked (this session's, by its marker; the map whole; the maintained
//     map whole, and there when a maintenance component takes part), the summary measured from
//     the start version's map and the staged one, the staging committed as the next version, the
//     oldest beyond `keep_versions` removed, the claim let go (the lock goes with the session's
//     last claim); the host lists the output ("site version").
//     A staging that is not whole commits nothing: the output is NOT saved (exit 4) and the
//     start version stays the newest.
//   map_request COMMIT_VERSION (`./ltm map commit`): a version in the middle of the session. The
//     mapping of the launch config is asked to save first (a SAVE_MAP request of this component's
//     own, answered on `status`), then the staging as it is is hard-linked aside, checked,
//     measured and committed as the next version (map/core/site_store.hpp: snapshot_staging,
//     commit_snapshot; atomic as the end-of-session commit; a save that ran meanwhile fails the
//     check and the snapshot is taken again, 3 times at most). The answer goes on `status`. The
//     session goes on saving into the staging; its end commits another version.
// Parameters: site_dir (required), keep_versions (10), site_version ("": the newest intact one),
// save_timeout_s (60: how long a commit on request waits for the mapping's save).
#include <chrono>
#include <filesystem>
#include <memory>
#include <optional>

#include "common/core/io_error.hpp"
#include "common/core/one_line.hpp"
#include "map/core/site_staging.hpp"
#include "map/core/site_store.hpp"
#include "runtime/component.hpp"
#include "runtime/convert/owned_message.hpp"
#include "runtime/convert/status.hpp"

namespace ltm::map {
namespace {

namespace fs = std::filesystem;
using runtime::PathCheck;
using runtime::TopicRole;

constexpr std::uint8_t kNew = 2;  // ltm_msgs/SegmentChange NEW

std::string same_path(const std::string& p) {
    std::error_code ec;
    const fs::path c = fs::weakly_canonical(fs::absolute(p), ec);
    return ec ? p : c.string();
}

class SiteComponent : public runtime::Component {
  public:
    explicit SiteComponent(runtime::ComponentContext& ctx)
        : ctx_(ctx), store_(ctx.params().path("site_dir", "", PathCheck::kNone)) {
        auto& p = ctx.params();
        if (store_.dir().empty()) p.fail("site_dir", "required: the site's folder");
        const int keep = p.get<int>("keep_versions", 10);
        if (keep < 1) p.fail("keep_versions", "must be >= 1");
        keep_ = std::size_t(keep);
        version_ = p.get<std::string>("site_version", "");
        save_timeout_s_ = p.get<double>("save_timeout_s", 60.0);
        if (!(save_timeout_s_ > 0)) p.fail("save_timeout_s", "must be > 0");
        check_others(p);
        bool made = false;
        try {
            claim_ = claim_staging(store_.dir(), &made);
        } catch (const common::IoError& e) {
            p.fail("site_dir", e.what());
        }
        if (!claim_->removed().empty() && made) ctx.log().warn(claim_->removed());
        if (!made)
            ctx.log().info(store_.staging_dir() + " is this session's staging (" +
                           claim_->mark().describe() + " by a component before this one): kept");
        try {
            session_ = resolve_site(store_.dir(), version_);
        } catch (const common::IoError& e) {
            p.fail(version_.empty() ? "site_dir" : "site_version", e.what());
        }
        for (const std::string& note : session_.notes) ctx.log().warn(note);
        ctx.log().info("site " + store_.dir() + ": the session starts from " + session_.describe() +
                       "; it will be saved as the next version (keeping " + std::to_string(keep_) +
                       ")");
        request_out_ = ctx.advertise<msg::MapRequest>("map_request", TopicRole::kState);
        status_out_ = ctx.advertise<msg::Status>("status", TopicRole::kState);
        ctx.subscribe<msg::MapRequest>("map_request", TopicRole::kState,
                                       [this](const msg::MapRequest& m) { on_request(m); });
        ctx.subscribe<msg::Status>("status", TopicRole::kState,
                                   [this](const msg::Status& m) { on_status(m); });
        ctx.add_timer(1.0, [this] { check_save_timeout(); });
        if (maintenance_) {
            ctx.subscribe<msg::MapChangeSet>(
                "map_changes", TopicRole::kMap, [this](const msg::MapChangeSet& m) {
                    removed_ += m.voxels_removed;
                    for (std::uint32_t i = 0; i < m.changes._length; ++i)
                        if (m.changes._buffer[i].reason == kNew)
                            added_ += m.changes._buffer[i].voxels._length / 3;
                });
        }
    }

    void on_shutdown() override {
        if (!claim_) return;  // committed already (a second shutdown)
        const std::string stays = session_.start
                                      ? session_.start->name + " stays the newest version"
                                      : std::string("the site still has no version");
        std::string problem = store_.staging_problem();
        if (problem.empty()) problem = claim_->staging_problem();  // never another session's
        if (problem.empty() && maintenance_ && !fs::exists(store_.staging_maintained_map_file()))
            problem = "the maintenance saved no maintained map into the staging";
        if (problem.empty()) {
            try {
                VersionSummary summary = measure_version(
                    store_.staging_map_dir(), session_.start ? session_.start->map_dir() : "",
                    session_.start ? session_.start->name : "");
                if (maintenance_) {
                    summary.voxels_removed = removed_;
                    summary.voxels_added = added_;
                }
                const SiteVersion made = store_.commit(summary, keep_);
                for (const std::string& name : store_.pruned())
                    ctx_.log().info("removed " + name + " (more than keep_versions " +
                                    std::to_string(keep_) + ")");
                ctx_.report_output("site version", made.dir, true,
                                   made.name + ": " + version_line(summary));
            } catch (const std::exception& e) {
                problem = common::one_line(e.what());
            }
        }
        if (!problem.empty())
            ctx_.report_output("site version", store_.staging_dir(), false,
                               problem + "; nothing committed, " + stays);
        claim_.reset();  // the lock goes with the session's last claim
    }

  private:
    // A commit on request: the mapping saves first (when the launch config has one).
    void on_request(const msg::MapRequest& m) {
        if (m.command != ltm_msgs_msg_MapRequest_Constants_COMMIT_VERSION) return;
        if (pending_) return answer(m.id, false, "a commit is under way already");
        if (!claim_) return answer(m.id, false, "the session has ended");
        pending_ = m.id;
        if (!mapping_) return commit_now();
        save_id_ = m.id ^ 0x5a5a5a5au;
        if (save_id_ == m.id) ++save_id_;
        save_deadline_ = std::chrono::steady_clock::now() +
                         std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                             std::chrono::duration<double>(save_timeout_s_));
        convert::Owned<msg::MapRequest> r;
        r->id = save_id_;
        r->command = ltm_msgs_msg_MapRequest_Constants_SAVE_MAP;
        request_out_.publish(*r);
        ctx_.log().info("request " + std::to_string(m.id) +
                        ": a version on request; the mapping saves first");
    }

    void on_status(const msg::Status& m) {
        if (!pending_ || !save_id_) return;
        const convert::StatusData s = convert::from_msg(m);
        if (s.request_id != save_id_) return;
        if (s.code == common::StatusCode::kMapRequestFailed) {
            save_id_ = 0;
            return finish_request(false, "the mapping could not save: " + s.message);
        }
        if (s.code != common::StatusCode::kMapRequestDone) return;
        save_id_ = 0;
        commit_now();
    }

    void check_save_timeout() {
        if (!pending_ || !save_id_ || std::chrono::steady_clock::now() < save_deadline_) return;
        save_id_ = 0;
        finish_request(false, "no answer from the mapping's save within " +
                                  std::to_string(int(save_timeout_s_)) + " s; nothing committed");
    }

    // The staging as it is now, committed as the next version (3 snapshots at most: a periodic
    // save that replaced files meanwhile fails the check).
    void commit_now() {
        if (const std::string p = claim_->staging_problem(); !p.empty())
            return finish_request(false, "nothing committed: " + p);
        std::string problem;
        for (int attempt = 0; attempt < 3; ++attempt) {
            try {
                const std::string snap = store_.snapshot_staging();
                VersionSummary summary =
                    measure_version(snap + "/map", session_.start ? session_.start->map_dir() : "",
                                    session_.start ? session_.start->name : "");
                if (maintenance_) {
                    summary.voxels_removed = removed_;
                    summary.voxels_added = added_;
                }
                const SiteVersion made = store_.commit_snapshot(snap, summary, keep_);
                ctx_.report_output("site version", made.dir, true,
                                   made.name + " (on request): " + version_line(summary));
                return finish_request(true, "committed " + made.name + " (" + made.dir + ")");
            } catch (const std::exception& e) {
                problem = common::one_line(e.what());
            }
        }
        finish_request(false, "nothing committed: " + problem);
    }

    void finish_request(bool ok, const std::string& text) {
        const std::uint32_t id = pending_;
        pending_ = 0;
        answer(id, ok, text);
    }

    void answer(std::uint32_t id, bool ok, const std::string& text) {
        convert::StatusData s;
        s.component = ctx_.name();
        s.level = ok ? convert::StatusLevel::kOk : convert::StatusLevel::kError;
        s.code = ok ? common::StatusCode::kMapRequestDone : common::StatusCode::kMapRequestFailed;
        s.message = "request " + std::to_string(id) + ": " + text;
        s.request_id = id;
        convert::log_status(ctx_.log(), s.level, s.message);
        status_out_.publish(*convert::to_msg(s));
    }

    // Every other component given a site must name this one, and the same version: one session,
    // one start. Notes whether a maintenance component takes part.
    void check_others(runtime::Parameters& p) {
        const runtime::LaunchConfig& launch = ctx_.launch_config();
        for (const runtime::ComponentSpec& c : launch.components) {
            if (c.name == ctx_.name() || !c.params || !c.params.IsMap() || !c.params["site_dir"])
                continue;
            runtime::Parameters other(c.params, launch.file, c.name);
            const std::string dir = other.path("site_dir", "", PathCheck::kNone);
            const std::string version = other.get<std::string>("site_version", "");
            if (same_path(dir) != same_path(store_.dir()))
                p.fail("site_dir", "component '" + c.name + "' has site_dir " + dir +
                                       ": every component of a session must use one site");
            if (version != version_)
                p.fail("site_version", "component '" + c.name + "' has site_version '" + version +
                                           "', this one '" + version_ +
                                           "': every component must start from one version");
            if (c.type == "maintenance") maintenance_ = true;
        }
        for (const runtime::ComponentSpec& c : launch.components)
            if (c.type == "mapping") mapping_ = true;
    }

    runtime::ComponentContext& ctx_;
    SiteStore store_;
    std::size_t keep_ = 10;
    std::string version_;
    bool maintenance_ = false;
    bool mapping_ = false;  // in this launch config: a commit on request asks it to save first
    double save_timeout_s_ = 60.0;
    runtime::Publisher<msg::MapRequest> request_out_;
    runtime::Publisher<msg::Status> status_out_;
    std::uint32_t pending_ = 0, save_id_ = 0;  // the request being answered, our save request
    std::chrono::steady_clock::time_point save_deadline_{};
    std::shared_ptr<StagingClaim> claim_;  // the session's, shared with its mapping, maintenance
    SiteSession session_;
    std::uint64_t removed_ = 0, added_ = 0;  // by the maintenance (map_changes)
};

}  // namespace
}  // namespace ltm::map

LTM_REGISTER_COMPONENT(ltm::map::SiteComponent, "site",
                       "a site's map versions: the session's start version, its lock, and the "
                       "staging committed as the next version at shutdown")
