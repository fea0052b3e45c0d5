#pragma once
// What the bridge sends a client, so that no client slows the pipeline: a message waits in the
// client's socket buffer or is dropped. Big messages (scans, local maps) go at most at
// `big_rate_hz` a subscription; nothing is queued past `max_buffered_bytes` a client (a slow or
// stalled client drops, and is told how many).
#include <cstddef>
#include <cstdint>
#include <map>

namespace ltm::bridge {

struct SendPolicyConfig {
    std::size_t big_message_bytes = 100 * 1024;
    double big_rate_hz = 5.0;
    std::size_t max_buffered_bytes = std::size_t{8} << 20;
};

class SendPolicy {
  public:
    enum class Verdict { kSend, kRateLimited, kBacklogged };
    explicit SendPolicy(SendPolicyConfig config = {}) : config_(config) {}

    // For one subscription's message of `size` bytes at `now_s`, with `buffered` bytes already
    // waiting in the client's socket.
    Verdict decide(std::uint32_t subscription, std::size_t size, double now_s,
                   std::size_t buffered);
    void forget(std::uint32_t subscription) { last_big_.erase(subscription); }

    std::uint64_t sent() const { return sent_; }
    std::uint64_t rate_limited() const { return rate_limited_; }
    std::uint64_t backlogged() const { return backlogged_; }

  private:
    SendPolicyConfig config_;
    std::map<std::uint32_t, double> last_big_;
    std::uint64_t sent_ = 0, rate_limited_ = 0, backlogged_ = 0;
};

}  // namespace ltm::bridge
