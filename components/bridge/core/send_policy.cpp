#include "bridge/core/send_policy.hpp"

namespace ltm::bridge {

SendPolicy::Verdict SendPolicy::decide(std::uint32_t subscription, std::size_t size, double now_s,
                                       std::size_t buffered) {
    if (buffered + size > config_.max_buffered_bytes && buffered > 0) {
        ++backlogged_;
        return Verdict::kBacklogged;
    }
    if (size >= config_.big_message_bytes && config_.big_rate_hz > 0.0) {
        const auto it = last_big_.find(subscription);
        if (it != last_big_.end() && now_s - it->second < 1.0 / config_.big_rate_hz) {
            ++rate_limited_;
            return Verdict::kRateLimited;
        }
        last_big_[subscription] = now_s;
    }
    ++sent_;
    return Verdict::kSend;
}

}  // namespace ltm::bridge
