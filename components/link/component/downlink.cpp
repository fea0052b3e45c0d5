// The base station's end of the link (issue 15). Takes the robot's `link/packets`, hands each
// packet on once and in order (ReceiveWindow), appends it to a journal on the base station's disk
// and acknowledges it (`link/ack`) once the journal is synced; then publishes the message on
// `/<robot>/<topic>` (`keyframe`, `local_map`) for the mapping. A restarted base station replays
// its journal first (the mapping starts again from the map it loaded, so nothing is applied
// twice) and tells the robot what it holds: the robot sends the rest.
// After handing packets on it tells the mapping in its process how far (`link/delivered`: run,
// seq, messages a topic so far), and the mapping records in every save what it holds
// (map/core/link_applied.hpp). With `site_dir` (the mapping's site) the journal keeps only what
// no committed version holds: at the start, what the start version holds is skipped (the mapping
// starts from it) and forgotten; a version committed while it runs (`./ltm map commit`) lets it
// forget what that version holds.
#include <dds/dds.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "common/core/io_error.hpp"
#include "link/component/link_clock.hpp"
#include "link/core/link_journal.hpp"
#include "link/core/payload_codec.hpp"
#include "link/core/receive_window.hpp"
#include "link/core/site_watermarks.hpp"
#include "link/core/write_fault.hpp"
#include "runtime/component.hpp"
#include "runtime/convert/dds_string.hpp"
#include "runtime/link_messages.hpp"

namespace ltm::link {
namespace {

using runtime::PathCheck;
using runtime::TopicRole;

class Downlink : public runtime::Component {
  public:
    explicit Downlink(runtime::ComponentContext& ctx) : ctx_(ctx) {
        auto& p = ctx.params();
        robot_ = p.get<std::string>("robot", robot_from_namespace(ctx.ns()));
        dir_ = p.path("journal_dir", "", PathCheck::kParentExists);
        out_ns_ = p.get<std::string>("output_namespace", "/" + robot_);
        const double ack_period = p.get<double>("ack_period_s", 0.5);
        // Readers in other processes, and recorders in this one, find the outputs by discovery:
        // the journal's replay waits for them this long.
        const double replay_delay = p.get<double>("replay_delay_s", 1.0);
        if (replay_delay < 0) p.fail("replay_delay_s", "must be >= 0");
        start_at_ = mono_s() + replay_delay;
        // Packets ahead of a gap wait in memory (each up to a local map's size): few arrive out of
        // order (DDS delivers in order; only the uplink's resends overtake), so few are kept.
        max_held_ = p.get<std::size_t>("max_held", 64);
        if (robot_.empty() || robot_.find('/') != std::string::npos)
            p.fail("robot", "a name without '/' (the robot's namespace)");
        if (dir_.empty()) p.fail("journal_dir", "required: where received packets are kept");
        if (out_ns_.empty() || out_ns_.front() != '/')
            p.fail("output_namespace", "an absolute namespace (\"/robot1\")");
        if (!(ack_period > 0)) p.fail("ack_period_s", "must be > 0");
        if (max_held_ == 0) p.fail("max_held", "must be > 0");
        // The journal is what a restarted base station replays to the mapping (nothing else holds
        // the session's messages until its version is committed): beyond this bound its oldest
        // packets go, said in one line, and a restart can no longer replay them.
        const double max_journal_mb = p.get<double>("max_journal_mb", 4096.0);
        if (!(max_journal_mb > 0)) p.fail("max_journal_mb", "must be > 0");
        journal_config_.max_bytes = static_cast<std::uint64_t>(max_journal_mb * (1 << 20));
        dir_ += "/" + robot_;
        base_run_ = new_run_id();
        // The site the mapping continues: what its start version holds is not replayed.
        const std::string site = p.path("site_dir", "", PathCheck::kNone);
        const std::string version = p.get<std::string>("site_version", "");
        const double site_poll = p.get<double>("site_poll_s", 2.0);
        if (!(site_poll > 0)) p.fail("site_poll_s", "must be > 0");
        if (!version.empty() && site.empty()) p.fail("site_version", "needs site_dir");
        if (!site.empty()) {
            try {
                site_.emplace(site, version, robot_);
                if (!site_->start_note().empty()) ctx.log().warn(site_->start_note());
            } catch (const common::IoError& e) {
                p.fail(version.empty() ? "site_dir" : "site_version", e.what());
            }
        }
        try {
            load_runs();
        } catch (const common::IoError& e) {
            p.fail("journal_dir", e.what());
        }
        if (site_) ctx.add_timer(site_poll, [this] { watch_site(); });
        // The outputs take the host's `topics:` role (base_station.yaml: stream, lossless with
        // back-pressure), else the role their readers declare (local_map: map, others: state).
        for (const std::string topic : {"keyframe", "local_map"}) output(topic);
        delivered_out_ =
            ctx.advertise<msg::LinkDelivered>(out_ns_ + "/link/delivered", TopicRole::kState);
        ctx.subscribe<msg::LinkPacket>("link/packets", TopicRole::kState,
                                       [this](const msg::LinkPacket& m) { on_packet(m); });
        ack_out_ = ctx.advertise<msg::LinkAck>("link/ack", TopicRole::kState);
        ctx.add_timer(ack_period, [this] { ack(); });
        ctx.add_timer(0.05, [this] { deliver_pending(); });
        ctx.add_timer(10.0, [this] { report(false); });
    }

    void on_shutdown() override {
        ack();
        report(true);
    }

  private:
    struct Run {
        std::unique_ptr<LinkJournal> journal;
        std::unique_ptr<ReceiveWindow> window;
        bool dirty = true;              // an acknowledgement is due
        std::uint64_t delivered = 0;    // every seq <= delivered was handed on (or skipped)
        std::uint64_t replay_last = 0;  // the journal's last seq when this base station started
        bool write_failed = false;      // a message not handed on: no more marks for this run
    };

    // A run's start when the site's start version holds its packets through `held`: those are
    // neither replayed nor resent (the window starts after them) and leave the journal.
    void start_after(std::uint64_t id, Run& r) {
        if (!site_) return;
        const auto it = site_->start().find(id);
        if (it == site_->start().end()) return;
        const std::uint64_t held = it->second;
        const std::uint64_t bytes = r.journal->bytes();
        r.journal->release_through(held);
        r.delivered = std::max(r.delivered, held);
        r.window = std::make_unique<ReceiveWindow>(r.journal->last_seq(), max_held_);
        ctx_.log().info("run " + run_hex(id) + ": packets through " + std::to_string(held) +
                        " are in site version " + site_->start_name() +
                        " (the mapping starts from it): not replayed, " +
                        std::to_string((bytes - r.journal->bytes()) >> 10) +
                        " KiB of journal released");
    }

    // A version committed while running: what it holds leaves the journal (a restart starts from
    // it). Only what was handed on, of course, which is all a version can hold.
    void watch_site() {
        std::string note;
        const auto newer = site_->poll(&note);
        if (!note.empty()) ctx_.log().warn(note);
        if (!newer) return;
        std::uint64_t freed = 0;
        std::size_t runs = 0;
        for (const auto& [id, through] : newer->through) {
            auto it = runs_.find(id);
            if (it == runs_.end()) continue;
            Run& r = it->second;
            const std::uint64_t upto = std::min(through, r.delivered);
            if (upto <= r.journal->released_through()) continue;
            const std::uint64_t bytes = r.journal->bytes();
            try {
                r.journal->release_through(upto);
            } catch (const std::exception& e) {
                ctx_.log().error(std::string("journal not released: ") + e.what());
                continue;
            }
            freed += bytes - r.journal->bytes();
            ++runs;
        }
        if (runs > 0)
            ctx_.log().info("site version " + newer->name + " holds " + std::to_string(runs) +
                            " run(s) of " + robot_ + " up to their packets " +
                            describe(newer->through) + ": " + std::to_string(freed >> 10) +
                            " KiB of journal released");
    }
    static std::string describe(const SiteWatermarks::Through& t) {
        std::string out;
        for (const auto& [id, through] : t)
            out += (out.empty() ? "" : ", ") + run_hex(id) + ":" + std::to_string(through);
        return out;
    }

    // Runs journaled by an earlier start of this base station.
    void load_runs() {
        std::vector<std::pair<std::int64_t, std::string>> found;  // first stamp, run folder
        for (const auto& [run, path] : run_folders(dir_)) {
            const std::string name = run_hex(run);
            Run r;
            r.journal = std::make_unique<LinkJournal>(path, journal_config_);
            if (!r.journal->recovery().empty())
                ctx_.log().warn("journal of run " + name + ": " + r.journal->recovery());
            r.window = std::make_unique<ReceiveWindow>(r.journal->last_seq(), max_held_);
            r.replay_last = r.journal->last_seq();
            const auto first = r.journal->read_from(0);
            found.emplace_back(first ? first->stamp_ns : 0, name);
            start_after(run, r);
            runs_[run] = std::move(r);
        }
        std::sort(found.begin(), found.end());
        for (const auto& f : found) order_.push_back(std::stoull(f.second, nullptr, 16));
    }

    // Everything journaled and not yet handed on, run by run in the order they started: a
    // restarted base station's journal first (the mapping gets it again, in order), then what
    // arrives. Delivery reads the journal back, so it is the same path either way.
    void deliver_pending() {
        if (!started_) {
            if (mono_s() < start_at_) return;
            started_ = true;
        }
        for (const std::uint64_t id : order_) {
            Run& r = runs_.at(id);
            const std::uint64_t before = r.delivered;
            while (r.delivered < r.journal->last_seq() && !ctx_.stop_requested()) {
                std::optional<JournalRecord> rec;
                try {
                    rec = r.journal->read_from(r.delivered + 1);
                } catch (const std::exception& e) {
                    ctx_.log().error(std::string("journal unreadable, run ") + run_hex(id) +
                                     " stalled: " + e.what());
                    break;
                }
                if (!rec) break;
                r.delivered = rec->seq;
                if (!deliver(*rec)) r.write_failed = true;
                if (rec->seq <= r.replay_last) {
                    ++replayed_;
                    if (rec->seq == r.replay_last)
                        ctx_.log().info("replayed the journal of run " + run_hex(id) +
                                        " up to packet " + std::to_string(r.replay_last) +
                                        " from " + r.journal->dir());
                }
            }
            if (r.delivered != before && !r.write_failed) mark(id, r);
        }
    }

    // Tells the mapping how far this run was handed on, and in how many messages a topic.
    void mark(std::uint64_t id, const Run& r) {
        msg::LinkDelivered m{};
        m.robot = const_cast<char*>(robot_.c_str());
        m.run = id;
        m.through = r.delivered;
        m.keyframes = by_topic_["keyframe"];
        m.local_maps = by_topic_["local_map"];
        m.map_changes = by_topic_["map_changes"];
        delivered_out_.publish(m);
    }

    runtime::RawWriterHandle* output(const std::string& topic) {
        auto it = writers_.find(topic);
        if (it != writers_.end()) return it->second.get();
        const runtime::MessageTypeInfo* info = nullptr;
        if (topic == "keyframe") info = type("ltm_msgs::msg::dds_::Keyframe_");
        if (topic == "local_map") info = type("ltm_msgs::msg::dds_::LocalMap_");
        return nullptr == info ? nullptr : add_writer(topic, info);
    }
    static const runtime::MessageTypeInfo* type(const std::string& dds_name) {
        return runtime::find_message_type_by_dds_name(dds_name);
    }
    runtime::RawWriterHandle* add_writer(const std::string& topic,
                                         const runtime::MessageTypeInfo* info) {
        const std::string name = out_ns_ + "/" + topic;
        const TopicRole declared = topic == "local_map" ? TopicRole::kMap : TopicRole::kState;
        runtime::QosProfile q = ctx_.role_profile(name, declared);
        auto w = ctx_.advertise_raw(name, info->descriptor, q);
        return (writers_[topic] = std::move(w)).get();
    }

    // False only when a message was not written to the mapping (it would then be missing from a
    // map whose record says it holds it); a packet no one can read is not held back for.
    bool deliver(const JournalRecord& r) {
        runtime::RawWriterHandle* w = nullptr;
        auto it = writers_.find(r.topic);
        if (it != writers_.end()) {
            w = it->second.get();
        } else if (const runtime::MessageTypeInfo* info = type(r.type)) {
            w = add_writer(r.topic, info);
        }
        if (!w) {
            ++undeliverable_;
            ctx_.log().warn("packet " + std::to_string(r.seq) + " on '" + r.topic +
                            "' is of an unknown type '" + r.type + "': kept, not delivered");
            return true;
        }
        std::vector<std::uint8_t> cdr;
        try {
            cdr = decode_payload(r.type, r.payload);
        } catch (const std::exception& e) {
            ++undeliverable_;
            ctx_.log().error("packet " + std::to_string(r.seq) + " on '" + r.topic +
                             "' does not decode: " + e.what());
            return true;
        }
        if (!runtime::write_raw(*w, cdr.data(), cdr.size())) {
            ctx_.log().error("packet " + std::to_string(r.seq) + " on '" + r.topic +
                             "' not handed on: its run's packets stay in the journal from here");
            return false;
        }
        ++delivered_;
        ++by_topic_[r.topic];
        return true;
    }

    void on_packet(const msg::LinkPacket& m) {
        if (convert::to_string(m.robot) != robot_) {
            ++other_robots_;
            return;
        }
        auto it = runs_.find(m.run);
        if (it == runs_.end()) {
            Run r;
            try {
                r.journal =
                    std::make_unique<LinkJournal>(dir_ + "/" + run_hex(m.run), journal_config_);
            } catch (const common::IoError& e) {
                ctx_.log().error(std::string("packets of run ") + run_hex(m.run) +
                                 " not kept: " + e.what());
                return;
            }
            r.window = std::make_unique<ReceiveWindow>(r.journal->last_seq(), max_held_);
            start_after(m.run, r);
            it = runs_.emplace(m.run, std::move(r)).first;
            order_.push_back(m.run);
            ctx_.log().info("run " + run_hex(m.run) + " of " + robot_ + " connected");
        }
        Run& run = it->second;
        JournalRecord rec;
        rec.seq = m.seq;
        rec.stamp_ns = m.stamp_ns;
        rec.topic = convert::to_string(m.topic);
        rec.type = convert::to_string(m.type);
        rec.payload.assign(m.payload._buffer, m.payload._buffer + m.payload._length);
        const std::uint64_t lost_before = run.window->stats().lost;
        std::vector<JournalRecord> ready = run.window->offer(std::move(rec), m.first_seq);
        if (run.window->stats().lost != lost_before)
            ctx_.log().error("run " + run_hex(m.run) + ": " +
                             std::to_string(run.window->stats().lost - lost_before) +
                             " packets lost for good (the robot no longer holds them)");
        run.dirty = true;
        for (const JournalRecord& r : ready) {
            try {
                const std::size_t dropped = run.journal->append(r);
                if (dropped > 0 && !capped_.count(m.run)) {
                    capped_.insert(m.run);
                    ctx_.log().error("journal of run " + run_hex(m.run) +
                                     " reached max_journal_mb: " + "its oldest packets go (" +
                                     std::to_string(dropped) +
                                     " now, more as it grows); a restarted base station can no " +
                                     "longer replay them to the mapping");
                }
                if (const std::string l = disk_.accepted("the journal's disk takes packets again");
                    !l.empty())
                    ctx_.log().info(l);
            } catch (const std::exception& e) {
                // Not kept, not acknowledged: the robot sends it again (and keeps it meanwhile).
                // One line when the disk starts refusing; the resends it refuses are counted.
                if (const std::string l = disk_.refused(
                        std::string("packet not journaled (the robot keeps it and resends it): ") +
                        e.what());
                    !l.empty())
                    ctx_.log().error(l);
                run.window = std::make_unique<ReceiveWindow>(run.journal->last_seq(), max_held_);
                break;
            }
        }
        deliver_pending();
    }

    // The robot learns what is safe here: synced to disk, then acknowledged. Every run is
    // acknowledged each period, so a robot sees a restarted base station within one period.
    void ack() {
        for (auto& [id, run] : runs_) {
            try {
                if (run.dirty) run.journal->sync();
            } catch (const std::exception& e) {
                ctx_.log().error(std::string("journal not synced: ") + e.what());
                continue;
            }
            run.dirty = false;
            msg::LinkAck a{};
            a.robot = const_cast<char*>(robot_.c_str());
            a.run = id;
            a.through = std::min(run.window->through(), run.journal->last_seq());
            a.base_run = base_run_;
            a.received = run.window->stats().received;
            a.duplicates = run.window->stats().duplicates;
            ack_out_.publish(a);
        }
    }

    void report(bool final) {
        std::uint64_t received = 0, dup = 0, lost = 0, held = 0;
        for (const auto& [id, run] : runs_) {
            received += run.window->stats().received;
            dup += run.window->stats().duplicates;
            lost += run.window->stats().lost;
            held += run.window->held();
        }
        const std::string line =
            std::string(final ? "final: " : "") + std::to_string(received) + " packets received (" +
            std::to_string(dup) + " duplicates), " + std::to_string(delivered_) +
            " messages delivered (" + std::to_string(replayed_) + " replayed from the journal), " +
            std::to_string(held) + " waiting for a gap, " + std::to_string(lost) + " lost" +
            (other_robots_
                 ? ", " + std::to_string(other_robots_) + " packets of other robots ignored"
                 : "") +
            (disk_.total() ? ", " + std::to_string(disk_.total()) +
                                 " refused by the journal's disk (left to the robot)"
                           : "");
        if (lost > 0 || undeliverable_ > 0 || disk_.failing()) {
            ctx_.log().warn(line);
        } else {
            ctx_.log().info(line);
        }
    }

    runtime::ComponentContext& ctx_;
    std::string robot_, dir_, out_ns_;
    std::size_t max_held_ = 64;
    std::uint64_t base_run_ = 0;
    std::map<std::uint64_t, Run> runs_;
    std::vector<std::uint64_t> order_;  // runs, in the order they started
    double start_at_ = 0.0;
    bool started_ = false;
    std::map<std::string, std::shared_ptr<runtime::RawWriterHandle>> writers_;
    std::uint64_t delivered_ = 0, replayed_ = 0, undeliverable_ = 0, other_robots_ = 0;
    WriteFault disk_;  // the journal's disk refusing appends: one line a spell
    JournalConfig journal_config_;
    std::set<std::uint64_t> capped_;  // runs whose journal reached max_journal_mb (said once)
    runtime::Publisher<msg::LinkAck> ack_out_;
    runtime::Publisher<msg::LinkDelivered> delivered_out_;
    std::map<std::string, std::uint64_t> by_topic_;  // messages handed on, by topic
    std::optional<SiteWatermarks> site_;
};

}  // namespace
}  // namespace ltm::link

LTM_REGISTER_COMPONENT(ltm::link::Downlink, "downlink",
                       "base-station side of the link: packets handed on once and in order, "
                       "journaled, acknowledged, and published for the mapping")
