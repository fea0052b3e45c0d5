// The robot's end of the link (issue 15): store and forward. Every message of the configured
// topics (read in-process from `input_prefix` + topic, e.g. the odometry's `onboard/keyframe`) is
// appended to a journal on the robot's disk and sent to the base station as a `link/packets`
// LinkPacket, in order, until the base station's `link/ack` says it is on the base station's
// disk. Sending never blocks the robot: a full link only delays it, an outage leaves the packets
// on disk, a restarted base station gets everything after what it holds. Nothing here blocks the
// odometry: its messages are only appended to the journal on arrival.
// A robot that restarts (a new run) first sends what its earlier runs left unacknowledged in
// backlog_dir, and numbers its keyframes, local maps and segments on after theirs (robot_ids.hpp:
// the restart reaches the base station's mapping as a new odometry segment of the same robot).
#include <dds/dds.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "common/core/io_error.hpp"
#include "link/component/link_clock.hpp"
#include "link/core/link_journal.hpp"
#include "link/core/payload_codec.hpp"
#include "link/core/robot_ids.hpp"
#include "link/core/send_window.hpp"
#include "link/core/write_fault.hpp"
#include "runtime/component.hpp"
#include "runtime/convert/dds_string.hpp"

namespace ltm::link {
namespace {

using runtime::PathCheck;
using runtime::QosProfile;
using runtime::TopicRole;

// The type of a forwarded topic: given, or known for ltm's own topics.
std::string default_type(const std::string& topic) {
    if (topic == "keyframe") return "ltm_msgs/msg/Keyframe";
    if (topic == "local_map") return "ltm_msgs/msg/LocalMap";
    if (topic == "map_changes") return "ltm_msgs/msg/MapChangeSet";
    if (topic == "loop_closure") return "ltm_msgs/msg/LoopClosure";
    return "";
}

const runtime::MessageTypeInfo* type_by_ros_name(const std::string& name) {
    for (const auto& t : runtime::known_message_types())
        if (t.ros_name == name) return &t;
    return nullptr;
}

class Uplink : public runtime::Component {
  public:
    explicit Uplink(runtime::ComponentContext& ctx) : ctx_(ctx) {
        auto& p = ctx.params();
        robot_ = p.get<std::string>("robot", robot_from_namespace(ctx.ns()));
        const std::vector<std::string> topics =
            p.get<std::vector<std::string>>("topics", {"keyframe", "local_map"});
        const std::vector<std::string> types = p.get<std::vector<std::string>>("types", {});
        const std::string prefix = p.get<std::string>("input_prefix", "onboard/");
        const std::string dir = p.path("backlog_dir", "", PathCheck::kParentExists);
        const double max_mb = p.get<double>("max_backlog_mb", 4096.0);
        SendConfig send;
        send.window_bytes =
            static_cast<std::uint64_t>(p.get<double>("window_mb", 16.0) * (1 << 20));
        send.resend_after_s = p.get<double>("resend_after_s", send.resend_after_s);
        send_period_s_ = p.get<double>("send_period_s", 0.01);
        // Cyclone's participant lease (10 s): after a longer silence the base station's reader was
        // dropped and matched again, and what was in flight must be sent again.
        rematch_after_s_ = p.get<double>("rematch_after_s", 10.0);
        if (!(rematch_after_s_ > 0)) p.fail("rematch_after_s", "must be > 0");
        drain_s_ = p.get<double>("drain_s", 10.0);
        // The journal and the link carry each message's wire form (payload_codec: lossless).
        codec_.level = p.get<int>("compression_level", codec_.level);
        if (codec_.level < 1 || codec_.level > 19)
            p.fail("compression_level", "expected a zstd level 1..19");
        if (robot_.empty() || robot_.find('/') != std::string::npos)
            p.fail("robot", "a name without '/' (the robot's namespace)");
        if (topics.empty()) p.fail("topics", "forward at least one topic");
        if (!types.empty() && types.size() != topics.size())
            p.fail("types", "one type per topic (" + std::to_string(topics.size()) + ")");
        if (dir.empty()) p.fail("backlog_dir", "required: where unacknowledged packets wait");
        if (!(max_mb > 0)) p.fail("max_backlog_mb", "must be > 0");
        if (!(send.window_bytes > 0)) p.fail("window_mb", "must be > 0");
        if (!(send.resend_after_s > 0)) p.fail("resend_after_s", "must be > 0");
        if (!(send_period_s_ > 0)) p.fail("send_period_s", "must be > 0");
        if (drain_s_ < 0) p.fail("drain_s", "must be >= 0");
        send_config_ = send;
        window_ = SendWindow(send);
        run_ = new_run_id();
        JournalConfig jc;
        jc.max_bytes = static_cast<std::uint64_t>(max_mb * (1 << 20));
        try {
            journal_ = std::make_unique<LinkJournal>(dir + "/" + run_hex(run_), jc);
            ids_ = std::make_unique<RobotIdRenumbering>(dir + "/ids");
            find_earlier_runs(dir);
        } catch (const common::IoError& e) {
            p.fail("backlog_dir", e.what());
        }
        for (std::size_t i = 0; i < topics.size(); ++i) {
            const std::string type = types.empty() ? default_type(topics[i]) : types[i];
            const runtime::MessageTypeInfo* info = type_by_ros_name(type);
            if (!info)
                p.fail(types.empty() ? "topics" : "types",
                       "no known message type for '" + topics[i] + "'" +
                           (type.empty() ? " (name it in `types`)" : ": '" + type + "'"));
            // Deep and reliable, so the odometry is never held up and nothing is overwritten
            // while the journal takes it.
            QosProfile q = ctx.role_profile(prefix + topics[i], TopicRole::kState);
            q.reliable = true;
            q.depth = std::max(q.depth, 1000);
            const std::string topic = topics[i], dds_type = info->dds_name;
            ctx.subscribe_raw(prefix + topics[i], info->descriptor, q,
                              [this, topic, dds_type](const std::vector<std::uint8_t>& cdr,
                                                      const dds_sample_info_t& si) {
                                  store(topic, dds_type, cdr, si.source_timestamp);
                              });
        }
        packets_ = ctx.advertise<msg::LinkPacket>("link/packets", TopicRole::kState);
        ctx.subscribe<msg::LinkAck>("link/ack", TopicRole::kState,
                                    [this](const msg::LinkAck& m) { on_ack(m); });
        ack_topic_ = ctx.resolve("link/ack");
        ctx.add_timer(send_period_s_, [this] { pump(); });
        ctx.add_timer(10.0, [this] { report(false); });
        // On the disk within a second (a power cut loses at most that); appends are flushed to
        // the kernel at once, so a crash of the process loses nothing.
        ctx.add_timer(1.0, [this] { sync(); });
        ctx.log().info("run " + run_hex(run_) + " of " + robot_ + ": backlog in " +
                       journal_->dir());
        const RobotIds& o = ids_->offsets();
        if (!(o == RobotIds{}))
            ctx.log().info(
                "this robot ran before: its keyframes, local maps and segments are "
                "numbered on from " +
                std::to_string(o.keyframe) + ", " + std::to_string(o.local_map) + " and " +
                std::to_string(o.segment) +
                " (the base station takes the restart as a new odometry segment)");
    }

    void on_shutdown() override {
        // The robot is stopping: give the link drain_s to take what is still unacknowledged.
        const double until = mono_s() + drain_s_;
        while ((window_.acked() < journal_->last_seq() || !earlier_.empty()) && mono_s() < until) {
            pump();
            take_acks();
            dds_sleepfor(DDS_MSECS(20));
        }
        save_ids();
        report(true);
    }

  private:
    // What an earlier run of this robot left unacknowledged: sent before this run's packets.
    struct Earlier {
        std::uint64_t run = 0;
        std::unique_ptr<LinkJournal> journal;
        SendWindow window;
    };

    // Earlier runs' folders in the backlog: those holding packets are sent first, oldest first;
    // empty ones are removed.
    void find_earlier_runs(const std::string& dir) {
        std::vector<std::pair<std::int64_t, Earlier>> found;
        for (const auto& [run, path] : run_folders(dir)) {
            if (run == run_) continue;
            const std::string name = run_hex(run);
            Earlier r;
            r.run = run;
            std::optional<JournalRecord> first;
            try {
                r.journal = std::make_unique<LinkJournal>(path);
                first = r.journal->read_from(0);
            } catch (const std::exception& err) {
                ctx_.log().error("backlog of earlier run " + name +
                                 " unreadable, left where it is: " + err.what());
                continue;
            }
            if (!r.journal->recovery().empty())
                ctx_.log().warn("backlog of earlier run " + name + ": " + r.journal->recovery());
            if (r.journal->empty()) {
                r.journal.reset();
                std::error_code ec;
                std::filesystem::remove_all(path, ec);
                continue;
            }
            r.window = SendWindow(send_config_);
            ctx_.log().info("earlier run " + name + " left " + std::to_string(r.journal->size()) +
                            " unacknowledged packets (" + std::to_string(r.journal->bytes() >> 20) +
                            " MiB): sent first");
            found.emplace_back(first ? first->stamp_ns : 0, std::move(r));
        }
        std::sort(found.begin(), found.end(),
                  [](const auto& a, const auto& b) { return a.first < b.first; });
        for (auto& f : found) earlier_.push_back(std::move(f.second));
    }

    void save_ids() {
        try {
            ids_->save();
        } catch (const std::exception& e) {
            ctx_.log().warn(std::string("robot ids not saved: ") + e.what());
        }
    }

    void store(const std::string& topic, const std::string& type,
               const std::vector<std::uint8_t>& cdr, dds_time_t source_ns) {
        JournalRecord r;
        r.seq = journal_->last_seq() + 1;
        r.stamp_ns = source_ns > 0 ? source_ns : wall_ns();
        r.topic = topic;
        r.type = type;
        try {
            std::vector<std::uint8_t> numbered = cdr;
            ids_->renumber(type, numbered);
            r.payload = encode_payload(type, numbered, codec_);
            const std::size_t dropped = journal_->append(r);
            if (dropped > 0) {
                dropped_ += dropped;
                ctx_.log().error("backlog full: the " + std::to_string(dropped) +
                                 " oldest unacknowledged packets dropped (" +
                                 std::to_string(dropped_) + " so far); raise max_backlog_mb");
            }
            if (const std::string l = disk_.accepted("the backlog's disk takes messages again");
                !l.empty())
                ctx_.log().info(l);
            ++stored_;
            unsynced_ = true;
            stored_bytes_ += cdr.size();
            wire_bytes_ += r.payload.size();
        } catch (const std::exception& e) {
            // Without its journal copy the message cannot be sent (packets are sent from the
            // journal): said in one line when the disk starts refusing (counted after that, in
            // the final report); its seq goes to the next message, so the base station sees no
            // gap.
            if (const std::string l = disk_.refused("a " + topic + " message is lost: " + e.what());
                !l.empty())
                ctx_.log().error(l);
        }
        pump();
    }

    void sync() {
        if (!unsynced_) return;
        unsynced_ = false;
        save_ids();  // before the records that use the numbers are on the disk
        try {
            journal_->sync();
        } catch (const std::exception& e) {
            ctx_.log().warn(std::string("backlog not synced: ") + e.what());
        }
    }

    void on_ack(const msg::LinkAck& m) {
        if (convert::to_string(m.robot) != robot_) return;
        if (m.run != run_) {
            on_earlier_ack(m);
            return;
        }
        const bool first = !window_.heard_base();
        const std::uint64_t restarts = window_.stats().base_restarts;
        const double now = mono_s();
        // Acknowledgements back after a silence (an outage, a base station away): say how much
        // waited, and later how long it took to deliver.
        if (!first && now - last_ack_s_ >= kSilence_s) {
            catch_up_to_ = journal_->last_seq();
            resumed_s_ = now;
            ctx_.log().info("acknowledgements resumed after " + seconds(now - last_ack_s_) +
                            " of silence: " + std::to_string(catch_up_to_ - window_.acked()) +
                            " packets (" + std::to_string(journal_->bytes() >> 20) +
                            " MiB) to deliver");
        }
        const bool rematched = !first && now - last_ack_s_ >= rematch_after_s_;
        last_ack_s_ = now;
        window_.on_ack(m.through, m.base_run, now);
        // Unless the match itself sent everything again already.
        if (rematched && !matched_again_) window_.resume_after_silence(now);
        matched_again_ = false;
        if (catch_up_to_ > 0 && window_.acked() >= catch_up_to_) {
            ctx_.log().info("backlog delivered " + seconds(now - resumed_s_) +
                            " after the base station was heard again");
            catch_up_to_ = 0;
        }
        if (first)
            ctx_.log().info("base station " + run_hex(m.base_run) + " holds " +
                            std::to_string(m.through) + " packets of this run");
        if (window_.stats().base_restarts != restarts) {
            ctx_.log().warn("the base station restarted (run " + run_hex(m.base_run) +
                            "): it holds " + std::to_string(m.through) +
                            " packets; sending the rest again");
            catch_up_to_ = journal_->last_seq();
            resumed_s_ = now;
        }
        if (window_.acked() > journal_->released_through()) {
            try {
                journal_->release_through(std::min(window_.acked(), journal_->last_seq()));
            } catch (const std::exception& e) {
                ctx_.log().warn(std::string("backlog not trimmed: ") + e.what());
            }
        }
    }

    void on_earlier_ack(const msg::LinkAck& m) {
        const auto it = std::find_if(earlier_.begin(), earlier_.end(),
                                     [&](const Earlier& e) { return e.run == m.run; });
        if (it == earlier_.end()) return;
        it->window.on_ack(m.through, m.base_run, mono_s());
        const std::uint64_t acked = std::min(it->window.acked(), it->journal->last_seq());
        try {
            if (acked > it->journal->released_through()) it->journal->release_through(acked);
        } catch (const std::exception& e) {
            ctx_.log().warn(std::string("backlog not trimmed: ") + e.what());
        }
        if (acked < it->journal->last_seq()) return;
        const std::string dir = it->journal->dir();
        ctx_.log().info("the backlog of earlier run " + run_hex(it->run) + " is delivered");
        earlier_.erase(it);
        std::error_code ec;
        std::filesystem::remove_all(dir, ec);
    }

    static std::string seconds(double s) {
        char b[32];
        std::snprintf(b, sizeof b, "%.1f s", s);
        return b;
    }

    void take_acks() {
        for (auto& s : ctx_.subscriptions()) {
            if (s.topic != ack_topic_) continue;
            void* samples[16] = {nullptr};
            dds_sample_info_t infos[16];
            const dds_return_t n = dds_take(s.reader, samples, infos, 16, 16);
            for (dds_return_t i = 0; i < n; ++i)
                if (infos[i].valid_data) on_ack(*static_cast<const msg::LinkAck*>(samples[i]));
            if (n > 0) dds_return_loan(s.reader, samples, n);
        }
    }

    // Earlier runs' backlogs first, then this run's; nothing while no base station listens (what
    // a volatile writer sends then reaches nobody, and a base station that never heard of a run
    // never acknowledges it). When one is matched again, what was in flight goes again.
    void pump() {
        if (packets_.matched() == 0) {
            unmatched_ = true;
            return;
        }
        if (unmatched_) {
            unmatched_ = false;
            matched_again_ = true;
            const double now = mono_s();
            window_.resume_after_silence(now);
            for (Earlier& e : earlier_) e.window.resume_after_silence(now);
        }
        for (Earlier& e : earlier_)
            if (!pump(e.run, *e.journal, e.window)) return;
        pump(run_, *journal_, window_);
    }

    // False when the link is full (or the backlog unreadable): nothing more now.
    bool pump(std::uint64_t run, const LinkJournal& journal, SendWindow& window) {
        const double now = mono_s();
        while (true) {
            const std::uint64_t first =
                journal.empty() ? journal.last_seq() + 1 : journal.first_seq();
            const auto seq = window.next(first, journal.last_seq(), now);
            if (!seq) return true;
            std::optional<JournalRecord> r;
            try {
                r = journal.read_from(*seq);
            } catch (const std::exception& e) {
                ctx_.log().error(std::string("backlog unreadable: ") + e.what());
                return false;
            }
            if (!r) return true;
            if (!send(run, *r, first)) return false;  // the link is full: later
            window.sent(r->seq, r->payload.size(), now);
        }
    }

    bool send(std::uint64_t run, const JournalRecord& r, std::uint64_t first_held) {
        msg::LinkPacket m{};
        m.robot = const_cast<char*>(robot_.c_str());
        m.run = run;
        m.seq = r.seq;
        m.first_seq = first_held;
        m.stamp_ns = r.stamp_ns;
        m.topic = const_cast<char*>(r.topic.c_str());
        m.type = const_cast<char*>(r.type.c_str());
        m.payload._buffer = const_cast<std::uint8_t*>(r.payload.data());
        m.payload._length = m.payload._maximum = static_cast<std::uint32_t>(r.payload.size());
        m.payload._release = false;
        const dds_return_t rc = packets_.try_publish(m);
        if (rc == DDS_RETCODE_OK) return true;
        if (rc != DDS_RETCODE_TIMEOUT) {
            const std::uint64_t n = ++send_errors_;
            if (n <= 3 || (n & (n - 1)) == 0)
                ctx_.log().warn(std::string("packet not sent (") + dds_strretcode(rc) + "), " +
                                std::to_string(n) + " so far");
        }
        return false;
    }

    void report(bool final) {
        const SendStats& s = window_.stats();
        const std::string line =
            std::string(final ? "final: " : "") + std::to_string(stored_) + " messages (" +
            std::to_string(stored_bytes_ >> 20) + " MiB, " + std::to_string(wire_bytes_ >> 20) +
            " MiB compressed) stored, " + std::to_string(s.sent) + " sent, " +
            std::to_string(s.resent) + " resent, acknowledged through " +
            std::to_string(window_.acked()) + " of " + std::to_string(journal_->last_seq()) +
            "; backlog " + std::to_string(journal_->size()) + " packets (" +
            std::to_string(journal_->bytes() >> 20) + " MiB)" +
            (earlier_.empty() ? ""
                              : ", and " + std::to_string(earlier_.size()) +
                                    " earlier runs' backlogs being sent") +
            (disk_.total() ? "; " + std::to_string(disk_.total()) +
                                 " messages lost: the backlog's disk refused them"
                           : std::string());
        if (final && window_.acked() < journal_->last_seq()) {
            ctx_.log().warn(line + ": the unacknowledged packets stay in " + journal_->dir());
        } else if (disk_.total() > 0) {
            ctx_.log().warn(line);
        } else {
            ctx_.log().info(line);
        }
        if (final)  // the journal is on disk as it goes: what the base station lacks is kept
            ctx_.report_output("uplink backlog", journal_->dir(), true,
                               std::to_string(journal_->last_seq() - window_.acked()) +
                                   " packets not acknowledged, kept for the next run");
    }

    runtime::ComponentContext& ctx_;
    std::string robot_, ack_topic_;
    std::uint64_t run_ = 0;
    double send_period_s_ = 0.01, drain_s_ = 10.0, rematch_after_s_ = 10.0;
    static constexpr double kSilence_s = 2.0;  // acknowledgements come every 0.5 s
    double last_ack_s_ = 0.0, resumed_s_ = 0.0;
    std::uint64_t catch_up_to_ = 0;
    std::unique_ptr<LinkJournal> journal_;
    SendConfig send_config_;
    SendWindow window_;
    std::unique_ptr<RobotIdRenumbering> ids_;
    std::vector<Earlier> earlier_;
    std::uint64_t stored_ = 0, stored_bytes_ = 0, wire_bytes_ = 0, dropped_ = 0, send_errors_ = 0;
    WriteFault disk_;  // the backlog's disk refusing appends: one line a spell
    PayloadCodecConfig codec_;
    bool unsynced_ = false;
    bool unmatched_ = true;       // no base station's reader matched (at the last pump)
    bool matched_again_ = false;  // matched again since the last acknowledgement
    runtime::Publisher<msg::LinkPacket> packets_;
};

}  // namespace
}  // namespace ltm::link

LTM_REGISTER_COMPONENT(ltm::link::Uplink, "uplink",
                       "robot side of the link: keyframes and local maps journaled on disk and "
                       "sent until the base station acknowledges them")
