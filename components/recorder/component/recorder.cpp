// Records DDS topics to an MCAP file: the CDR bytes as received, unchanged.
//   topics: [points, /robot/odometry]   names (relative ones in the host's namespace), or
//   all: true                           every topic published on the domain whose type ltm knows
// Topics are found through DDS discovery (the DCPSPublication built-in topic), so publishers
// may appear at any time; each is read with QoS matching its writer. Writing happens on its own
// thread behind a bounded queue: the recorder never stalls a publisher, and drops are reported.
// The disk (issue 28): the folder of recordings is kept within `max_total_mb` / `keep_newest`
// (oldest whole files removed, never this one), and recording stops with one line, the file
// closed and readable, when the disk's free space falls under `min_free_mb` or this file alone
// outgrows `max_total_mb`.
#include <sys/statvfs.h>
#include <time.h>

#include <filesystem>
#include <map>
#include <memory>
#include <set>

#include "common/core/io_error.hpp"
#include "recorder/async/async_mcap_writer.hpp"
#include "recorder/core/recording_budget.hpp"
#include "runtime/component.hpp"
#include "runtime/idl_schema.hpp"
#include "runtime/topic_names.hpp"
#include "runtime/worker.hpp"

namespace ltm::recorder {
namespace {

using runtime::PathCheck;
using runtime::QosProfile;

std::uint64_t now_ns() {
    timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    return static_cast<std::uint64_t>(ts.tv_sec) * 1000000000ull + ts.tv_nsec;
}

class Recorder : public runtime::Component {
  public:
    explicit Recorder(runtime::ComponentContext& ctx) : ctx_(ctx) {
        auto& p = ctx.params();
        const std::string file = p.path("file", "", PathCheck::kParentExists);
        if (file.empty()) p.fail("file", "required parameter is missing (the .mcap file to write)");
        all_ = p.get<bool>("all", false);
        for (const auto& t : p.get<std::vector<std::string>>("topics", {})) {
            std::string err;
            const std::string abs = runtime::resolve_name(t, ctx.ns(), ctx.name(), err);
            if (abs.empty()) p.fail("topics", err);
            wanted_.insert(runtime::dds_topic_name(abs));
        }
        if (all_ == !wanted_.empty()) p.fail("topics", "give either topics: [...] or all: true");
        McapWriterConfig wc;
        const std::string compression = p.get<std::string>("compression", "zstd");
        if (!parse_compression(compression, wc.compression))
            p.fail("compression", "expected zstd, lz4 or none, got '" + compression + "'");
        wc.chunk_size = static_cast<std::size_t>(p.get<double>("chunk_size_mb", 4.0) * (1 << 20));
        wc.sync = p.get<bool>("sync", false);
        AsyncWriterConfig ac;
        ac.max_queue_bytes = static_cast<std::size_t>(p.get<double>("queue_mb", 512.0) * (1 << 20));
        ac.thread_name = runtime::worker_thread_name(ctx.name(), "write");
        // The disk's budget: the folder of recordings (with sub-folders: a day's output each).
        budget_dir_ = p.path("budget_dir", "", PathCheck::kNone);
        const double max_total_mb = p.get<double>("max_total_mb", 0.0);
        const int keep_newest = p.get<int>("keep_newest", 0);
        min_free_mb_ = p.get<double>("min_free_mb", 512.0);
        if (!(max_total_mb >= 0)) p.fail("max_total_mb", "must be >= 0 (0: no bound)");
        if (keep_newest < 0) p.fail("keep_newest", "must be >= 0 (0: no bound)");
        if (!(min_free_mb_ >= 0)) p.fail("min_free_mb", "must be >= 0 (0: no floor)");
        budget_.max_total_bytes = static_cast<std::uint64_t>(max_total_mb * (1 << 20));
        budget_.keep_newest = static_cast<std::size_t>(keep_newest);
        if (budget_dir_.empty() && (budget_.max_total_bytes > 0 || budget_.keep_newest > 0))
            budget_dir_ = std::filesystem::path(file).parent_path().string();
        if (!budget_dir_.empty() && budget_.max_total_bytes == 0 && budget_.keep_newest == 0)
            p.fail("budget_dir", "give max_total_mb or keep_newest (the bounds of the folder)");
        try {
            writer_ = std::make_unique<AsyncMcapWriter>(
                std::make_unique<McapWriter>(file, wc), ac,
                [this](const std::string& line) { ctx_.log().warn(line); });
        } catch (const common::IoError& e) {
            p.fail("file", e.what());
        }
        file_ = file;
        check_disk();
        // Every publication on the domain, past and future.
        const dds_entity_t reader = dds_create_reader(
            ctx.participant(), DDS_BUILTIN_TOPIC_DCPSPUBLICATION, nullptr, nullptr);
        if (reader < 0)
            throw std::runtime_error(std::string("cannot read DCPSPublication: ") +
                                     dds_strretcode(reader));
        ctx.subscribe_reader(reader, [this](const void* s) {
            on_publication(*static_cast<const dds_builtintopic_endpoint_t*>(s));
        });
        // The free space every half second (a statvfs), the folder's budget (a walk of it) and
        // the report every 5 s.
        ctx.add_timer(0.5, [this] { check_free_space(); });
        ctx.add_timer(5.0, [this] {
            check_disk();
            report(false);
        });
    }

    void on_shutdown() override {
        const AsyncWriterStats st = writer_->close();
        report(true, &st);
        ctx_.report_output(
            "recording", file_, !st.failed,
            st.failed ? st.error
                      : std::to_string(st.writer.messages) + " messages" +
                            (st.dropped() ? ", " + std::to_string(st.dropped()) + " dropped"
                                          : std::string()) +
                            (stopped_ ? "; stopped early: " + stop_reason_ : std::string()));
        for (const auto& t : wanted_)
            if (!recording_.count(t))
                ctx_.log().warn("topic " + t + " was never published; nothing recorded for it");
    }

  private:
    // The folder within its budget, the disk above its floor; else recording stops (one line).
    void check_disk() {
        if (stopped_ || writer_->stats().failed) return;
        if (!budget_dir_.empty()) {
            const BudgetResult r = enforce_budget(budget_dir_, budget_, {file_});
            if (!r.removed.empty() || !r.error.empty())
                (r.error.empty() ? ctx_.log().info(describe(r)) : ctx_.log().warn(describe(r)));
            if (r.protected_over_budget)
                return stop("this recording alone is " + std::to_string(r.kept_bytes >> 20) +
                            " MiB, over max_total_mb " +
                            std::to_string(budget_.max_total_bytes >> 20));
        }
        check_free_space();
    }
    void check_free_space() {
        if (stopped_ || min_free_mb_ <= 0) return;
        struct statvfs fs {};
        const std::string folder = std::filesystem::path(file_).parent_path().string();
        if (::statvfs(folder.empty() ? "." : folder.c_str(), &fs) == 0) {
            const double free_mb = static_cast<double>(fs.f_bavail) * fs.f_frsize / (1 << 20);
            if (free_mb < min_free_mb_)
                stop(std::to_string(static_cast<long long>(free_mb)) + " MiB free on the disk, " +
                     "under min_free_mb " + std::to_string(static_cast<long long>(min_free_mb_)) +
                     " (the room is kept for the map's saves)");
        }
    }
    void stop(const std::string& why) {
        stopped_ = true;
        if (writer_->stats().failed) return;  // said already (the disk refused a write)
        stop_reason_ = why;
        const AsyncWriterStats st = writer_->close();
        ctx_.log().error("recording stopped: " + why + "; " + file_ + " closed with " +
                         std::to_string(st.writer.messages) + " messages" +
                         (st.failed ? " (" + st.error + ")" : std::string()));
    }

    void on_publication(const dds_builtintopic_endpoint_t& pub) {
        const std::string topic = pub.topic_name ? pub.topic_name : "";
        const std::string type = pub.type_name ? pub.type_name : "";
        if (topic.rfind("rt/", 0) != 0) return;  // not a ROS-mapped topic (ltm's private probes)
        if (!all_ && !wanted_.count(topic)) return;
        if (recording_.count(topic) || refused_.count(topic)) return;
        const runtime::MessageTypeInfo* info = runtime::find_message_type_by_dds_name(type);
        if (!info) {
            refused_.insert(topic);
            ctx_.log().warn(
                "not recording " + topic + ": type " + type +
                " is unknown to ltm (Cyclone DDS 0.10 as packaged has no type discovery)");
            return;
        }
        QosProfile qos = runtime::matching_reader_profile(pub.qos, 64);
        qos.keep_all = qos.reliable;  // no resource limits: the reader never blocks the writer
        const std::uint16_t schema = schema_for(*info);
        const std::uint16_t channel = writer_->add_channel(
            schema, topic, "cdr",
            {{"reliability", qos.reliable ? "reliable" : "best_effort"},
             {"durability", qos.transient_local ? "transient_local" : "volatile"}});
        recording_[topic] = channel;
        ctx_.subscribe_raw(
            topic.substr(2), info->descriptor, qos,
            [this, channel](const std::vector<std::uint8_t>& cdr, const dds_sample_info_t& si) {
                const std::uint64_t publish = si.source_timestamp > 0
                                                  ? static_cast<std::uint64_t>(si.source_timestamp)
                                                  : now_ns();
                writer_->push(channel, now_ns(), publish, cdr.data(), cdr.size());
            });
        ctx_.log().info("recording " + topic + " (" + info->ros_name + ")");
    }

    std::uint16_t schema_for(const runtime::MessageTypeInfo& info) {
        auto it = schemas_.find(info.dds_name);
        if (it != schemas_.end()) return it->second;
        const std::uint16_t id =
            writer_->add_schema(info.dds_name, "omgidl", runtime::idl_schema_text(info.ros_name));
        schemas_[info.dds_name] = id;
        return id;
    }

    void report(bool final_report, const AsyncWriterStats* final_stats = nullptr) {
        const AsyncWriterStats st = final_stats ? *final_stats : writer_->stats();
        if (!final_report && (st.accepted == last_accepted_ || st.failed)) return;
        last_accepted_ = st.accepted;
        std::string line = std::to_string(final_report ? st.writer.messages : st.accepted) +
                           " messages on " + std::to_string(recording_.size()) + " topics, " +
                           std::to_string(st.writer.file_bytes / (1 << 20)) + " MiB in " + file_;
        if (st.dropped() > 0) {
            line += "; DROPPED " + std::to_string(st.dropped()) + " (";
            for (const auto& [topic, n] : st.dropped_by_topic)
                line += topic + ": " + std::to_string(n) + " ";
            line += ")";
        }
        if (st.failed) line += "; " + st.error;
        (st.dropped() || st.failed ? ctx_.log().warn(line) : ctx_.log().info(line));
    }

    runtime::ComponentContext& ctx_;
    std::unique_ptr<AsyncMcapWriter> writer_;
    std::string file_, budget_dir_, stop_reason_;
    RecordingBudget budget_;
    double min_free_mb_ = 512.0;
    bool stopped_ = false;
    bool all_ = false;
    std::set<std::string> wanted_, refused_;
    std::map<std::string, std::uint16_t> recording_, schemas_;
    std::uint64_t last_accepted_ = 0;
};

}  // namespace
}  // namespace ltm::recorder

LTM_REGISTER_COMPONENT(ltm::recorder::Recorder, "recorder",
                       "records DDS topics (CDR unchanged) to an MCAP file")
