#include "runtime/component_context.hpp"

#include <algorithm>

#include "runtime/dds_error.hpp"
#include "runtime/raw_cdr.hpp"
#include "runtime/topic_names.hpp"

namespace ltm::runtime {

ComponentContext::ComponentContext(Domain& domain, const LaunchConfig& config,
                                   const ComponentSpec& spec)
    : domain_(domain),
      config_(config),
      spec_(spec),
      params_(spec.params, config.file, spec.name),
      log_(spec.name) {
    for (const auto& [from, to] : spec_.remaps) remap_used_[from] = false;
}

ComponentContext::~ComponentContext() {
    // Readers and writers first (their read conditions go with them); topics stay with the domain.
    for (auto& s : subscriptions_) dds_delete(s.reader);
    for (auto& w : writers_) dds_delete(w->writer);
}

void ComponentContext::fail_topic(const std::string& topic, const std::string& problem) const {
    auto it = spec_.remap_lines.find(topic);
    throw ConfigError(config_.file, it != spec_.remap_lines.end() ? it->second : spec_.line,
                      spec_.name + ".topic " + topic, problem);
}

std::string ComponentContext::resolve(const std::string& topic) {
    std::string name = topic;
    if (auto it = spec_.remaps.find(topic); it != spec_.remaps.end()) {
        name = it->second;
        remap_used_[topic] = true;
    }
    std::string err;
    const std::string abs = resolve_name(name, config_.ns, spec_.name, err);
    if (abs.empty()) fail_topic(topic, err);
    return abs;
}

std::string ComponentContext::ns() const { return normalise_namespace(config_.ns); }

void ComponentContext::check_remaps_used() const {
    for (const auto& [from, used] : remap_used_) {
        if (used) continue;
        std::string topics;
        for (const auto& s : subscriptions_) topics += (topics.empty() ? "" : ", ") + s.topic;
        for (const auto& w : writers_) topics += (topics.empty() ? "" : ", ") + w->topic;
        throw ConfigError(config_.file, spec_.remap_lines.at(from), spec_.name + ".remap." + from,
                          "component type '" + spec_.type + "' has no topic '" + from + "'" +
                              (topics.empty() ? std::string(" (it has no topics)")
                                              : " (its topics: " + topics + ")"));
    }
}

dds_entity_t ComponentContext::topic_entity(const std::string& topic,
                                            const dds_topic_descriptor_t* desc,
                                            std::string& absolute) {
    absolute = resolve(topic);
    try {
        return domain_.topic(dds_topic_name(absolute), desc);
    } catch (const std::invalid_argument& e) {
        fail_topic(topic, e.what());
    }
}

ComponentContext::Subscription& ComponentContext::add_reader(const std::string& topic,
                                                             const dds_topic_descriptor_t* desc,
                                                             const QosProfile& profile) {
    Subscription s;
    const dds_entity_t t = topic_entity(topic, desc, s.topic);
    Qos qos;
    fill_reader_qos(profile, qos.get());
    s.reader = check_dds(dds_create_reader(domain_.participant(), t, qos.get(), nullptr),
                         "creating a reader for " + s.topic);
    s.readcond =
        check_dds(dds_create_readcondition(s.reader, DDS_ANY_STATE), "creating a read condition");
    subscriptions_.push_back(std::move(s));
    attach(subscriptions_.back());
    return subscriptions_.back();
}

void ComponentContext::add_subscription(const std::string& topic, TopicRole role,
                                        const dds_topic_descriptor_t* desc,
                                        std::function<void(const void*)> handler) {
    add_reader(topic, desc, domain_.profile(resolve(topic), role)).handler = std::move(handler);
}

void ComponentContext::attach_waitset(dds_entity_t waitset) {
    waitset_ = waitset;
    for (const auto& s : subscriptions_) attach(s);
}

void ComponentContext::attach(const Subscription& s) {
    if (waitset_ > 0)
        check_dds(dds_waitset_attach(waitset_, s.readcond, 0), "attaching a read condition");
}

bool ComponentContext::Subscription::duplicate(const dds_sample_info_t& info) {
    auto [it, fresh] = last_source_time.try_emplace(info.publication_handle, info.source_timestamp);
    if (fresh) return false;
    if (it->second == info.source_timestamp) return true;
    it->second = info.source_timestamp;
    return false;
}

std::uint32_t ComponentContext::matched_publishers(const std::string& topic) {
    const std::string abs = resolve(topic);
    std::uint32_t n = 0;
    for (const auto& s : subscriptions_) {
        dds_subscription_matched_status_t st{};
        if (s.topic == abs && dds_get_subscription_matched_status(s.reader, &st) == DDS_RETCODE_OK)
            n += st.current_count;
    }
    return n;
}

QosProfile ComponentContext::role_profile(const std::string& topic, TopicRole declared) {
    return domain_.profile(resolve(topic), declared);
}

void ComponentContext::subscribe_raw(const std::string& topic, const dds_topic_descriptor_t* desc,
                                     const QosProfile& profile, RawHandler handler) {
    add_reader(topic, desc, profile).raw_handler = std::move(handler);
}

void ComponentContext::subscribe_reader(dds_entity_t reader,
                                        std::function<void(const void*)> handler) {
    Subscription s;
    s.topic = "(built-in)";
    s.reader = reader;
    s.readcond =
        check_dds(dds_create_readcondition(reader, DDS_ANY_STATE), "creating a read condition");
    s.handler = std::move(handler);
    subscriptions_.push_back(std::move(s));
    attach(subscriptions_.back());
}

template <class Handle>
std::shared_ptr<Handle> ComponentContext::make_writer(const std::string& topic,
                                                      const dds_topic_descriptor_t* desc,
                                                      const QosProfile& profile) {
    auto h = std::make_shared<Handle>();
    const dds_entity_t t = topic_entity(topic, desc, h->topic);
    h->profile = profile;
    Qos qos;
    fill_writer_qos(profile, qos.get());
    h->writer = check_dds(dds_create_writer(domain_.participant(), t, qos.get(), nullptr),
                          "creating a writer for " + h->topic);
    h->stop = &stop_;
    h->log = log_;
    writers_.push_back(h);
    return h;
}

std::shared_ptr<RawWriterHandle> ComponentContext::advertise_raw(const std::string& topic,
                                                                 const dds_topic_descriptor_t* desc,
                                                                 const QosProfile& profile) {
    auto h = make_writer<RawWriterHandle>(topic, desc, profile);
    h->type = sertype_of(domain_.participant(), desc);
    return h;
}

std::shared_ptr<WriterHandle> ComponentContext::add_writer(const std::string& topic, TopicRole role,
                                                           const dds_topic_descriptor_t* desc) {
    return make_writer<WriterHandle>(topic, desc, domain_.profile(resolve(topic), role));
}

void ComponentContext::add_timer(double period_s, std::function<void()> fn) {
    Timer t;
    t.period_s = period_s < 0 ? 0 : period_s;
    t.next = std::chrono::steady_clock::now();
    t.fn = std::move(fn);
    timers_.push_back(std::move(t));
}

std::chrono::steady_clock::time_point ComponentContext::work_deadline() const {
    using clock = std::chrono::steady_clock;
    const std::int64_t deadline = stop_deadline_;
    if (deadline == std::numeric_limits<std::int64_t>::max()) return clock::time_point::max();
    const auto now = clock::now();
    const clock::time_point end{clock::duration(deadline)};
    return end <= now ? now : now + (end - now) / 2;
}

void ComponentContext::request_stop(std::chrono::steady_clock::time_point deadline) {
    if (deadline != std::chrono::steady_clock::time_point::max())
        stop_deadline_ = deadline.time_since_epoch().count();
    {
        std::lock_guard<std::mutex> lock(sleep_mutex_);
        stop_ = true;
    }
    sleep_cv_.notify_all();
}

bool ComponentContext::sleep_until(std::chrono::steady_clock::time_point deadline) {
    std::unique_lock<std::mutex> lock(sleep_mutex_);
    return !sleep_cv_.wait_until(lock, deadline, [this] { return stop_.load(); });
}

void ComponentContext::report_output(const std::string& what, const std::string& path, bool ok,
                                     const std::string& detail) {
    std::lock_guard<std::mutex> lock(outputs_mutex_);
    for (auto& o : outputs_) {
        if (o.what == what && o.path == path) {
            o.ok = ok;
            o.detail = detail;
            return;
        }
    }
    outputs_.push_back({what, path, ok, detail});
}

std::vector<ComponentContext::Output> ComponentContext::outputs() const {
    std::lock_guard<std::mutex> lock(outputs_mutex_);
    return outputs_;
}

bool ComponentContext::has_role_override(const std::string& topic) {
    const std::string abs = resolve(topic);
    return domain_.role(abs, TopicRole::kSensor) != TopicRole::kSensor ||
           domain_.role(abs, TopicRole::kState) != TopicRole::kState;
}

void ComponentContext::finished() {
    // Reliable readers elsewhere get everything before the host may decide to stop.
    for (const auto& w : writers_)
        if (w->profile.reliable) dds_wait_for_acks(w->writer, DDS_SECS(2));
    finished_ = true;
}

namespace {

// The source timestamp of the next sample of `h`: now, strictly after the writer's previous one.
// A write retried after a timeout keeps its timestamp, so that a reader which already took the
// sample (another reader was full) recognises the copy (ComponentRunner drops it).
dds_time_t next_source_time(WriterHandle& h) {
    dds_time_t last = h.last_source_time.load();
    while (true) {
        const dds_time_t t = std::max<dds_time_t>(dds_time(), last + 1);
        if (h.last_source_time.compare_exchange_weak(last, t)) return t;
    }
}

// Writes with `write(timestamp)` until it succeeds, retrying while a keep-all reader is full.
template <class Write>
bool write_with_backpressure(WriterHandle& h, Write&& write) {
    const dds_time_t ts = next_source_time(h);
    while (true) {
        const dds_return_t rc = write(ts);
        if (rc == DDS_RETCODE_OK) {
            ++h.published;
            return true;
        }
        // Back-pressure: a keep-all reader's queue is full. Retry until it drains or we stop.
        // Readers that took the sample before the timeout drop the retry's copy (same writer,
        // same source timestamp): each sample is delivered exactly once.
        if (rc == DDS_RETCODE_TIMEOUT && h.profile.keep_all && !(h.stop && h.stop->load())) {
            ++h.retried;
            continue;
        }
        const std::uint64_t n = ++h.failed;
        if (n <= 3 || (n & (n - 1)) == 0)
            h.log.warn("publishing on " + h.topic + " failed (" + dds_strretcode(rc) + "), " +
                       std::to_string(n) + " so far");
        return false;
    }
}

}  // namespace

bool write_sample(WriterHandle& h, const void* sample) {
    return write_with_backpressure(
        h, [&](dds_time_t ts) { return dds_write_ts(h.writer, sample, ts); });
}

bool write_raw(RawWriterHandle& h, const std::uint8_t* cdr, std::size_t size) {
    return write_with_backpressure(
        h, [&](dds_time_t ts) { return write_cdr(h.writer, h.type, cdr, size, ts); });
}

}  // namespace ltm::runtime
