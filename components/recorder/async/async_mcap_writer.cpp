#include "recorder/async/async_mcap_writer.hpp"

#include <pthread.h>

#include <algorithm>
#include <stdexcept>

namespace ltm::recorder {

namespace {
constexpr std::size_t kPoolSize = 32;  // payload buffers kept for reuse
}

AsyncMcapWriter::AsyncMcapWriter(std::unique_ptr<McapWriter> writer, AsyncWriterConfig config,
                                 Report report)
    : writer_(std::move(writer)), config_(config), report_(std::move(report)) {
    if (!writer_) throw std::invalid_argument("AsyncMcapWriter needs a writer");
    for (const auto& [id, s] : writer_->schemas()) {
        schema_known_[id] = true;
        next_schema_ = static_cast<std::uint16_t>(id + 1);
    }
    for (const auto& [id, c] : writer_->channels()) {
        topics_[id] = c.topic;
        next_channel_ = static_cast<std::uint16_t>(id + 1);
    }
    stats_.writer = writer_->stats();
    stats_.failed = writer_->failed() || !writer_->is_open();
    thread_ = std::thread([this] { run(); });
}

AsyncMcapWriter::~AsyncMcapWriter() { close(); }

std::uint16_t AsyncMcapWriter::add_schema(const std::string& name, const std::string& encoding,
                                          const std::string& data) {
    Item item;
    item.kind = Item::Kind::kSchema;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        if (next_schema_ == 0) throw std::invalid_argument("more than 65535 schemas");
        item.schema = Schema{next_schema_, name, encoding, data};
        schema_known_[next_schema_] = true;
        ++next_schema_;
    }
    const std::uint16_t id = item.schema.id;
    enqueue(std::move(item));
    return id;
}

std::uint16_t AsyncMcapWriter::add_channel(std::uint16_t schema_id, const std::string& topic,
                                           const std::string& message_encoding,
                                           const std::map<std::string, std::string>& metadata) {
    Item item;
    item.kind = Item::Kind::kChannel;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        if (schema_id != 0 && !schema_known_.count(schema_id)) {
            throw std::invalid_argument("channel '" + topic + "': unknown schema id " +
                                        std::to_string(schema_id));
        }
        if (next_channel_ == 0) throw std::invalid_argument("more than 65535 channels");
        item.channel = Channel{next_channel_, schema_id, topic, message_encoding, metadata};
        topics_[next_channel_] = topic;
        ++next_channel_;
    }
    const std::uint16_t id = item.channel.id;
    enqueue(std::move(item));
    return id;
}

void AsyncMcapWriter::enqueue(Item&& item) {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        queue_.push_back(std::move(item));
        ++stats_.queued_messages;
    }
    cv_.notify_one();
}

void AsyncMcapWriter::drop(std::uint16_t channel_id, bool after_failure) {
    ++(after_failure ? stats_.dropped_after_failure : stats_.dropped_queue_full);
    const auto t = topics_.find(channel_id);
    ++stats_.dropped_by_topic[t == topics_.end() ? "channel " + std::to_string(channel_id)
                                                 : t->second];
}

bool AsyncMcapWriter::admit(std::uint16_t channel_id, std::size_t size) {
    if (stats_.failed || closing_) {
        drop(channel_id, true);
        return false;
    }
    if (stats_.queued_messages >= config_.max_queue_messages ||
        stats_.queued_bytes + size > config_.max_queue_bytes) {
        drop(channel_id, false);
        return false;
    }
    ++stats_.accepted;
    ++stats_.queued_messages;  // reserved now, so that concurrent pushes see the limit
    stats_.queued_bytes += size;
    stats_.peak_queued_bytes = std::max(stats_.peak_queued_bytes, stats_.queued_bytes);
    return true;
}

bool AsyncMcapWriter::push(std::uint16_t channel_id, std::uint64_t log_time,
                           std::uint64_t publish_time, const void* data, std::size_t size) {
    Item item;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        if (!admit(channel_id, size)) return false;
        if (!pool_.empty()) {
            item.data = std::move(pool_.back());
            pool_.pop_back();
        }
    }
    const auto* p = static_cast<const std::uint8_t*>(data);
    item.data.assign(p, p + size);  // the copy happens outside the lock
    item.channel_id = channel_id;
    item.log_time = log_time;
    item.publish_time = publish_time;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        queue_.push_back(std::move(item));
    }
    cv_.notify_one();
    return true;
}

bool AsyncMcapWriter::push(std::uint16_t channel_id, std::uint64_t log_time,
                           std::uint64_t publish_time, std::vector<std::uint8_t>&& data) {
    Item item;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        if (!admit(channel_id, data.size())) return false;
        item.data = std::move(data);
        item.channel_id = channel_id;
        item.log_time = log_time;
        item.publish_time = publish_time;
        queue_.push_back(std::move(item));
    }
    cv_.notify_one();
    return true;
}

AsyncWriterStats AsyncMcapWriter::stats() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return stats_;
}

void AsyncMcapWriter::maybe_report(std::unique_lock<std::mutex>& lock, bool force) {
    if (!report_) return;
    const auto now = std::chrono::steady_clock::now();
    const std::uint64_t drops = stats_.dropped();
    if (drops == reported_drops_) return;
    if (!force && now - last_report_ < std::chrono::duration<double>(config_.report_period_s)) {
        return;
    }
    std::string line = "recorder: " + std::to_string(drops - reported_drops_) +
                       " message(s) dropped (" + std::to_string(drops) + " in total: ";
    bool first = true;
    for (const auto& [topic, n] : stats_.dropped_by_topic) {
        line += (first ? "" : ", ") + topic + " " + std::to_string(n);
        first = false;
    }
    line += stats_.failed ? "; writing stopped)" : "; the disk cannot keep up)";
    reported_drops_ = drops;
    last_report_ = now;
    lock.unlock();
    report_(line);
    lock.lock();
}

void AsyncMcapWriter::run() {
    if (!config_.thread_name.empty())
        pthread_setname_np(pthread_self(), config_.thread_name.substr(0, 15).c_str());
    std::unique_lock<std::mutex> lock(mutex_);
    const auto idle = std::chrono::duration<double>(config_.idle_flush_s);
    while (true) {
        const bool woke = cv_.wait_for(lock, idle, [&] { return !queue_.empty() || closing_; });
        maybe_report(lock, false);
        if (queue_.empty()) {
            if (closing_) break;
            if (!woke && !stats_.failed && writer_->chunk_open()) {
                lock.unlock();
                const WriteStatus st = writer_->flush();
                lock.lock();
                stats_.writer = writer_->stats();
                if (st != WriteStatus::kOk) {
                    stats_.failed = true;
                    stats_.error = writer_->error();
                }
            }
            continue;
        }
        Item item = std::move(queue_.front());
        queue_.pop_front();
        const bool failed_before = stats_.failed;
        lock.unlock();
        WriteStatus st = WriteStatus::kOk;
        std::string error;
        switch (item.kind) {
            case Item::Kind::kSchema:
                writer_->add_schema_record(item.schema);
                break;
            case Item::Kind::kChannel:
                writer_->add_channel_record(item.channel);
                break;
            case Item::Kind::kMessage:
                if (!failed_before) {
                    st = writer_->write(item.channel_id, item.log_time, item.publish_time,
                                        item.data.data(), item.data.size());
                }
                break;
        }
        lock.lock();
        --stats_.queued_messages;
        if (item.kind == Item::Kind::kMessage) {
            stats_.queued_bytes -= item.data.size();
            if (failed_before)
                drop(item.channel_id, true);
            else if (st == WriteStatus::kOk)
                ++stats_.written;
            if (pool_.size() < kPoolSize) pool_.push_back(std::move(item.data));
        }
        stats_.writer = writer_->stats();
        if (!failed_before && st != WriteStatus::kOk) {
            stats_.failed = true;
            stats_.error = writer_->error().empty() ? write_status_name(st) : writer_->error();
            const std::string line = "recorder: " + stats_.error;
            if (report_) {
                lock.unlock();
                report_(line);
                lock.lock();
            }
        }
    }
    lock.unlock();
    const WriteStatus st = writer_->close();
    lock.lock();
    stats_.writer = writer_->stats();
    if (st != WriteStatus::kOk && !stats_.failed) {
        stats_.failed = true;
        stats_.error = writer_->error();
    }
    maybe_report(lock, true);
}

AsyncWriterStats AsyncMcapWriter::close() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        if (!closed_) {
            closing_ = true;
            closed_ = true;
        }
    }
    cv_.notify_one();
    if (thread_.joinable()) thread_.join();
    std::lock_guard<std::mutex> lock(mutex_);
    return stats_;
}

}  // namespace ltm::recorder
