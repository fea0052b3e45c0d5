#pragma once
// What a component gets from its host: its parameters, topics (with remaps, namespace and QoS
// applied), timers, a logger and a stop flag.
#include <dds/dds.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "runtime/domain.hpp"
#include "runtime/held_memory.hpp"
#include "runtime/logging.hpp"
#include "runtime/messages.hpp"
#include "runtime/parameters.hpp"
#include "runtime/publisher.hpp"
#include "runtime/qos.hpp"

namespace ltm::runtime {

class ComponentContext {
  public:
    ComponentContext(Domain& domain, const LaunchConfig& config, const ComponentSpec& spec);
    ~ComponentContext();
    ComponentContext(const ComponentContext&) = delete;
    ComponentContext& operator=(const ComponentContext&) = delete;

    const std::string& name() const { return spec_.name; }
    const std::string& type() const { return spec_.type; }
    // The host's namespace ("" or "/robot").
    std::string ns() const;
    Parameters& params() { return params_; }
    // The host's launch config: what the other components of this process are set to (read, e.g.,
    // to take the odometry's effective settings rather than its preset's).
    const LaunchConfig& launch_config() const { return config_; }
    const Logger& log() const { return log_; }

    // An input: `handler` runs on this component's thread for every sample taken.
    template <class T>
    void subscribe(const std::string& topic, TopicRole role,
                   std::function<void(const T&)> handler) {
        add_subscription(
            topic, role, MessageTraits<T>::descriptor(),
            [h = std::move(handler)](const void* sample) { h(*static_cast<const T*>(sample)); });
    }
    // Writers currently matched with this component's reader(s) of `topic` (a declared name):
    // is its producer running?
    std::uint32_t matched_publishers(const std::string& topic);
    // An output.
    template <class T>
    Publisher<T> advertise(const std::string& topic, TopicRole role) {
        return Publisher<T>(add_writer(topic, role, MessageTraits<T>::descriptor()));
    }

    // Raw CDR input (serialized bytes with their encapsulation header), for recording: `qos` as
    // given. May also be called while running, from the component's own thread.
    using RawHandler =
        std::function<void(const std::vector<std::uint8_t>& cdr, const dds_sample_info_t& info)>;
    void subscribe_raw(const std::string& topic, const dds_topic_descriptor_t* desc,
                       const QosProfile& qos, RawHandler handler);
    // Raw CDR output, for replay.
    std::shared_ptr<RawWriterHandle> advertise_raw(const std::string& topic,
                                                   const dds_topic_descriptor_t* desc,
                                                   const QosProfile& qos);
    // A reader the component created itself (a built-in topic such as DCPSPublication); the
    // context owns it from now on and `handler` gets each valid sample on the component's thread.
    void subscribe_reader(dds_entity_t reader, std::function<void(const void* sample)> handler);
    dds_entity_t participant() const { return domain_.participant(); }
    QosProfile role_profile(const std::string& topic, TopicRole declared);

    // Calls `fn` every `period_s` seconds on this component's thread; period 0 calls it whenever
    // no input is waiting (a source's production loop).
    void add_timer(double period_s, std::function<void()> fn);

    // A source produces data on its own; the host may exit once every source has finished and
    // every component has processed its input.
    void declare_source() { source_ = true; }
    // Called by a source when it has published everything (waits for reliable readers' acks).
    void finished();
    bool is_source() const { return source_; }
    bool is_finished() const { return finished_; }
    bool stop_requested() const { return stop_.load(); }
    // Until when a component's background work may go on once a stop is requested: half the
    // time left to the host's stop deadline (the other half is for its final saves); far in the
    // future before a stop. Workers stop with it: Worker::stop(ctx.work_deadline()).
    std::chrono::steady_clock::time_point work_deadline() const;
    // Sleeps until `deadline` or a stop request; false when stopped. For pacing a source.
    bool sleep_until(std::chrono::steady_clock::time_point deadline);
    // True when the launch config's `topics:` section sets the role of this declared topic.
    bool has_role_override(const std::string& topic);

    // What a component wrote for the user (a map, a recording, a mesh): the host lists every
    // output when it stops and exits non-zero, naming it, when one could not be saved. Any
    // thread. `detail`: one line (what it holds, or why it failed).
    struct Output {
        std::string what;  // "map", "maintained map", "recording", "mesh", ...
        std::string path;
        bool ok = true;
        std::string detail;
    };
    void report_output(const std::string& what, const std::string& path, bool ok,
                       const std::string& detail = "");
    std::vector<Output> outputs() const;

    // What the component holds now, by part (bytes; any thread, at the component's own pace:
    // a few times a minute is plenty). The host's minute log line lists them (held_memory.hpp).
    void report_memory(const std::string& part, std::size_t bytes) { held_.set(part, bytes); }
    std::vector<HeldPart> held_memory() const { return held_.parts(); }

    // The absolute ROS name a declared topic resolves to (remap and namespace applied).
    std::string resolve(const std::string& topic);
    // Throws ConfigError for a remap of a topic the component never declared.
    void check_remaps_used() const;

    // --- used by the runner ---
    struct Subscription {
        std::string topic;
        dds_entity_t reader = 0;
        dds_entity_t readcond = 0;
        std::function<void(const void*)> handler;  // typed samples
        RawHandler raw_handler;                    // or raw CDR
        std::vector<std::uint8_t> buffer;          // reused by raw takes
        // Each writer's last source timestamp: a sample with the same writer and timestamp as
        // the previous one is the copy of a write retried after back-pressure (write_sample)
        // and is dropped, so that a handler sees every sample exactly once.
        std::map<dds_instance_handle_t, dds_time_t> last_source_time;
        // True for a sample already delivered (and remembers this one).
        bool duplicate(const dds_sample_info_t& info);
    };
    struct Timer {
        double period_s = 0;
        std::chrono::steady_clock::time_point next;
        std::function<void()> fn;
    };
    // A deque: subscriptions added by a handler do not move the one being dispatched.
    std::deque<Subscription>& subscriptions() { return subscriptions_; }
    void attach_waitset(dds_entity_t waitset);
    std::vector<Timer>& timers() { return timers_; }
    void request_stop(std::chrono::steady_clock::time_point deadline =
                          std::chrono::steady_clock::time_point::max());
    const std::vector<std::shared_ptr<WriterHandle>>& writers() const { return writers_; }

  private:
    void add_subscription(const std::string& topic, TopicRole role,
                          const dds_topic_descriptor_t* desc,
                          std::function<void(const void*)> handler);
    std::shared_ptr<WriterHandle> add_writer(const std::string& topic, TopicRole role,
                                             const dds_topic_descriptor_t* desc);
    [[noreturn]] void fail_topic(const std::string& topic, const std::string& problem) const;
    dds_entity_t topic_entity(const std::string& topic, const dds_topic_descriptor_t* desc,
                              std::string& absolute);
    Subscription& add_reader(const std::string& topic, const dds_topic_descriptor_t* desc,
                             const QosProfile& profile);
    template <class Handle>
    std::shared_ptr<Handle> make_writer(const std::string& topic,
                                        const dds_topic_descriptor_t* desc,
                                        const QosProfile& profile);

    Domain& domain_;
    const LaunchConfig& config_;
    ComponentSpec spec_;
    Parameters params_;
    Logger log_;
    std::map<std::string, bool> remap_used_;
    void attach(const Subscription& s);
    std::deque<Subscription> subscriptions_;
    dds_entity_t waitset_ = 0;
    std::vector<Timer> timers_;
    std::vector<std::shared_ptr<WriterHandle>> writers_;
    std::atomic<bool> stop_{false};
    std::atomic<std::int64_t> stop_deadline_{std::numeric_limits<std::int64_t>::max()};
    std::mutex sleep_mutex_;
    std::condition_variable sleep_cv_;
    bool source_ = false;
    std::atomic<bool> finished_{false};
    mutable std::mutex outputs_mutex_;
    std::vector<Output> outputs_;  // the last report of each (what, path)
    HeldMemory held_;
};

}  // namespace ltm::runtime
