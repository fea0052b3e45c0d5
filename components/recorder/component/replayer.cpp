// Replays an MCAP recording onto DDS: the recorded CDR bytes, unchanged.
//   rate: R        original timing scaled by R (default 1)
//   fast: true     as fast as readers take samples, reliable with back-pressure: nothing dropped
//   topics: [...]  a subset (names as recorded, e.g. /robot/points); start / duration: a window [s]
//   loop: true     start again at the end
// Topics keep their recorded names; the launch config's `remap:` renames them
// (remap: {/robot/points: /replay/points}).
#include <time.h>

#include <algorithm>
#include <memory>

#include "common/core/io_error.hpp"
#include "common/core/progress.hpp"
#include "recorder/core/mcap_reader.hpp"
#include "runtime/component.hpp"

namespace ltm::recorder {
namespace {

using runtime::PathCheck;
using runtime::QosProfile;

class Replayer : public runtime::Component {
  public:
    explicit Replayer(runtime::ComponentContext& ctx) : ctx_(ctx) {
        auto& p = ctx.params();
        const std::string file = p.path("file", "", PathCheck::kFileExists);
        if (file.empty())
            p.fail("file", "required parameter is missing (the .mcap file to replay)");
        rate_ = p.get<double>("rate", 1.0);
        if (rate_ <= 0) p.fail("rate", "must be positive");
        fast_ = p.get<bool>("fast", false);
        loop_ = p.get<bool>("loop", false);
        wait_for_readers_ = p.get<int>("wait_for_readers", fast_ ? 1 : 0);
        wait_timeout_s_ = p.get<double>("wait_timeout_s", 30.0);
        const double start = p.get<double>("start", 0.0), duration = p.get<double>("duration", 0.0);
        if (start < 0 || duration < 0) p.fail("start", "start and duration must not be negative");
        try {
            reader_ = std::make_unique<McapReader>(file);
        } catch (const common::IoError& e) {
            p.fail("file", e.what());
        }
        if (!reader_->problem().empty())
            ctx.log().warn(reader_->problem() + " (replaying what is intact)");
        const std::vector<std::string> topics = p.get<std::vector<std::string>>("topics", {});
        // Recorded topics are DDS names ("rt/robot/points"); users name them as ROS names.
        std::string existing;
        for (const auto& [id, ch] : reader_->channels())
            existing += (existing.empty() ? "" : ", ") + ros_name(ch.topic);
        for (const auto& t : topics) {
            bool found = false;
            for (const auto& [id, ch] : reader_->channels())
                found |= ros_name(ch.topic) == t || ch.topic == t;
            if (!found)
                p.fail("topics", "no topic '" + t + "' in " + file + " (topics: " + existing + ")");
        }
        for (const auto& [id, ch] : reader_->channels()) {
            const std::string name = ros_name(ch.topic);
            if (!topics.empty() && std::find(topics.begin(), topics.end(), name) == topics.end() &&
                std::find(topics.begin(), topics.end(), ch.topic) == topics.end())
                continue;
            const auto schema = reader_->schemas().find(ch.schema_id);
            const runtime::MessageTypeInfo* info =
                schema == reader_->schemas().end()
                    ? nullptr
                    : runtime::find_message_type_by_dds_name(schema->second.name);
            if (!info || ch.message_encoding != "cdr") {
                ctx.log().warn("skipping " + ch.topic + ": not a CDR message of a type ltm knows");
                continue;
            }
            QosProfile qos =
                fast_ ? ctx.role_profile(name, runtime::TopicRole::kStream) : QosProfile{};
            if (fast_) {
                qos.reliable = true;
                qos.keep_all = true;
            } else {
                auto meta = [&](const char* key) {
                    auto it = ch.metadata.find(key);
                    return it == ch.metadata.end() ? std::string() : it->second;
                };
                qos.reliable = meta("reliability") != "best_effort";
                qos.transient_local = meta("durability") == "transient_local";
                qos.depth = 64;
            }
            writers_[id] = ctx.advertise_raw(name, info->descriptor, qos);
            selected_.push_back(ch.topic);
        }
        if (writers_.empty())
            p.fail("file", "nothing to replay (no topic of a known type selected)");
        window_.topics = selected_;
        const std::uint64_t first = reader_->statistics().message_start_time;
        window_.start_time = first + static_cast<std::uint64_t>(start * 1e9);
        if (duration > 0)
            window_.end_time = window_.start_time + static_cast<std::uint64_t>(duration * 1e9);
        ctx.declare_source();
        ctx.add_timer(0.0, [this] { step(); });
    }

    void on_shutdown() override {
        if (jitter_ms_.empty()) return;
        std::sort(jitter_ms_.begin(), jitter_ms_.end());
        const auto q = [&](double f) {
            return jitter_ms_[static_cast<std::size_t>(f * (jitter_ms_.size() - 1))];
        };
        ctx_.log().info("timing error against the recording x" + std::to_string(rate_) +
                        ": median " + std::to_string(q(0.5)) + " ms, p99 " +
                        std::to_string(q(0.99)) + " ms, max " + std::to_string(jitter_ms_.back()) +
                        " ms over " + std::to_string(jitter_ms_.size()) + " messages");
    }

  private:
    static std::string ros_name(const std::string& dds) {
        return dds.rfind("rt/", 0) == 0 ? dds.substr(2) : dds;
    }

    void step() {
        using clock = std::chrono::steady_clock;
        if (!cursor_) {
            if (!ready()) return;
            cursor_ = std::make_unique<MessageCursor>(reader_->messages(window_));
            start_wall_ = clock::now();
            t0_ = 0;
            if (!progress_)
                progress_ = std::make_unique<common::Progress>(ctx_.name(), total(), "messages");
        }
        MessageView m;
        if (!cursor_->next(m)) {
            for (const auto& problem : reader_->problems()) ctx_.log().warn(problem);
            if (loop_) {
                cursor_.reset();
                return;
            }
            progress_->finish();
            ctx_.log().info("replayed " + std::to_string(sent_) + " messages");
            ctx_.finished();
            return;
        }
        auto it = writers_.find(m.channel->id);
        if (it == writers_.end()) return;
        if (t0_ == 0) t0_ = m.log_time;
        if (!fast_) {
            const double offset = (m.log_time - t0_) * 1e-9 / rate_;
            const auto due = start_wall_ + std::chrono::duration_cast<clock::duration>(
                                               std::chrono::duration<double>(offset));
            if (!ctx_.sleep_until(due)) return;
            jitter_ms_.push_back(
                std::chrono::duration<double, std::milli>(clock::now() - due).count());
        }
        if (runtime::write_raw(*it->second, m.data, m.size)) ++sent_;
        progress_->update(sent_);
    }

    bool ready() {
        if (wait_for_readers_ <= 0) return true;
        if (waiting_since_ == std::chrono::steady_clock::time_point{})
            waiting_since_ = std::chrono::steady_clock::now();
        std::uint32_t matched = 0;  // readers summed over the replayed topics
        for (const auto& [id, w] : writers_) {
            dds_publication_matched_status_t st{};
            dds_get_publication_matched_status(w->writer, &st);
            matched += st.current_count;
        }
        if (static_cast<int>(matched) >= wait_for_readers_) return true;
        if (std::chrono::steady_clock::now() - waiting_since_ >
            std::chrono::duration<double>(wait_timeout_s_)) {
            ctx_.log().warn("only " + std::to_string(matched) + " of " +
                            std::to_string(wait_for_readers_) + " readers after " +
                            std::to_string(wait_timeout_s_) + " s; replaying anyway");
            return true;
        }
        ctx_.sleep_until(std::chrono::steady_clock::now() + std::chrono::milliseconds(5));
        return false;
    }

    std::size_t total() const {
        std::size_t n = 0;
        for (const auto& [id, count] : reader_->statistics().channel_message_counts)
            if (writers_.count(id)) n += count;
        return n;
    }

    runtime::ComponentContext& ctx_;
    std::unique_ptr<McapReader> reader_;
    std::unique_ptr<MessageCursor> cursor_;
    std::map<std::uint16_t, std::shared_ptr<runtime::RawWriterHandle>> writers_;
    std::vector<std::string> selected_;
    ReadOptions window_;
    double rate_ = 1.0, wait_timeout_s_ = 30.0;
    bool fast_ = false, loop_ = false;
    int wait_for_readers_ = 0;
    std::uint64_t t0_ = 0, sent_ = 0;
    std::chrono::steady_clock::time_point start_wall_, waiting_since_;
    std::unique_ptr<common::Progress> progress_;
    std::vector<double> jitter_ms_;
};

}  // namespace
}  // namespace ltm::recorder

LTM_REGISTER_COMPONENT(ltm::recorder::Replayer, "replayer",
                       "replays an MCAP recording onto DDS (recorded CDR unchanged), timed or as "
                       "fast as readers take it")
