// Records DDS topics to an MCAP file: the CDR bytes as received, unchanged.
//   topics: [points, /robot/odometry]   names (relative ones in the host's namespace), or
//   all: true                           every topic published on the domain whose type ltm knows
// Topics are found through DDS discovery (the DCPSPublication built-in topic), so publishers
// may appear at any time; each is read with QoS matching its writer. Writing happens on its own
// thread behind a bounded queue: the recorder never stalls a publisher, and drops are reported.
#include <time.h>

#include <map>
#include <memory>
#include <set>

#include "common/core/io_error.hpp"
#include "recorder/async/async_mcap_writer.hpp"
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
        try {
            writer_ = std::make_unique<AsyncMcapWriter>(
                std::make_unique<McapWriter>(file, wc), ac,
                [this](const std::string& line) { ctx_.log().warn(line); });
        } catch (const common::IoError& e) {
            p.fail("file", e.what());
        }
        file_ = file;
        // Every publication on the domain, past and future.
        const dds_entity_t reader = dds_create_reader(
            ctx.participant(), DDS_BUILTIN_TOPIC_DCPSPUBLICATION, nullptr, nullptr);
        if (reader < 0)
            throw std::runtime_error(std::string("cannot read DCPSPublication: ") +
                                     dds_strretcode(reader));
        ctx.subscribe_reader(reader, [this](const void* s) {
            on_publication(*static_cast<const dds_builtintopic_endpoint_t*>(s));
        });
        ctx.add_timer(5.0, [this] { report(false); });
    }

    void on_shutdown() override {
        const AsyncWriterStats st = writer_->close();
        report(true, &st);
        ctx_.report_output(
            "recording", file_, !st.failed,
            st.failed ? st.error
                      : std::to_string(st.writer.messages) + " messages" +
                            (st.dropped() ? ", " + std::to_string(st.dropped()) + " dropped"
                                          : std::string()));
        for (const auto& t : wanted_)
            if (!recording_.count(t))
                ctx_.log().warn("topic " + t + " was never published; nothing recorded for it");
    }

  private:
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
        if (!final_report && st.accepted == last_accepted_) return;
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
    std::string file_;
    bool all_ = false;
    std::set<std::string> wanted_, refused_;
    std::map<std::string, std::uint16_t> recording_, schemas_;
    std::uint64_t last_accepted_ = 0;
};

}  // namespace
}  // namespace ltm::recorder

LTM_REGISTER_COMPONENT(ltm::recorder::Recorder, "recorder",
                       "records DDS topics (CDR unchanged) to an MCAP file")
