#include "link/core/send_window.hpp"

#include <algorithm>

namespace ltm::link {

void SendWindow::go_back(double now) {
    in_flight_.clear();
    in_flight_bytes_ = 0;
    next_ = acked_ + 1;
    stalled_since_ = now;
}

void SendWindow::on_ack(std::uint64_t through, std::uint64_t base_run, double now) {
    if (wait_s_ <= 0.0) wait_s_ = config_.resend_after_s;
    if (base_run != base_run_) {
        if (base_run_ != 0) ++stats_.base_restarts;
        base_run_ = base_run;
        // A restarted base station holds what it says, no more (its journal is the truth).
        acked_ = through;
        wait_s_ = config_.resend_after_s;
        last_heard_ = now;
        go_back(now);
        return;
    }
    // The stall clock runs only while the base station is heard: after a silence (an outage)
    // DDS repairs what was in flight once the link is back, which takes time of its own.
    if (now - last_heard_ >= wait_s_) stalled_since_ = now;
    last_heard_ = now;
    if (through > acked_) {
        acked_ = through;
        while (!in_flight_.empty() && in_flight_.begin()->first <= through) {
            in_flight_bytes_ -= in_flight_.begin()->second;
            in_flight_.erase(in_flight_.begin());
        }
        next_ = std::max(next_, acked_ + 1);
        stalled_since_ = now;
        wait_s_ = config_.resend_after_s;
        return;
    }
    // Acknowledgements come but do not advance while packets are out: some were lost for good.
    if (!in_flight_.empty() && now - stalled_since_ >= wait_s_) {
        ++stats_.go_backs;
        go_back(now);
        wait_s_ = std::min(2.0 * wait_s_, config_.max_resend_after_s);
    }
}

void SendWindow::resume_after_silence(double now) {
    if (in_flight_.empty()) return;
    ++stats_.go_backs;
    go_back(now);
    wait_s_ = config_.resend_after_s;
}

std::optional<std::uint64_t> SendWindow::next(std::uint64_t first_held, std::uint64_t last_held,
                                              double /*now*/) {
    next_ = std::max({next_, first_held, acked_ + 1});
    if (first_held > last_held || next_ > last_held) return std::nullopt;
    if (in_flight_bytes_ >= config_.window_bytes) return std::nullopt;
    return next_;
}

void SendWindow::sent(std::uint64_t seq, std::uint64_t bytes, double now) {
    if (in_flight_.empty()) stalled_since_ = now;  // the clock runs while something is out
    if (in_flight_.emplace(seq, bytes).second) in_flight_bytes_ += bytes;
    if (seq <= highest_) {
        ++stats_.resent;
        stats_.resent_bytes += bytes;
    } else {
        ++stats_.sent;
        stats_.sent_bytes += bytes;
        highest_ = seq;
    }
    next_ = seq + 1;
}

}  // namespace ltm::link
