#pragma once
// The robot's side of the link: which journaled packet to send next. New packets go out in seq
// order while less than window_bytes are unacknowledged. The base station acknowledges what it
// has stored; when its acknowledgements keep coming but stop advancing for resend_after_s (a
// packet DDS could not deliver: an outage longer than the writer's history, a reader matched
// again), sending goes back to the first unacknowledged packet, waiting twice as long before the
// next go-back (at most max_resend_after_s). A base station that restarted (a new base_run) gets
// everything after what it says it has, at once.
#include <cstdint>
#include <map>
#include <optional>

namespace ltm::link {

struct SendConfig {
    std::uint64_t window_bytes = 16ull << 20;  // unacknowledged bytes in flight at most
    double resend_after_s = 3.0;
    double max_resend_after_s = 24.0;
};

struct SendStats {
    std::uint64_t sent = 0, resent = 0;  // packets
    std::uint64_t sent_bytes = 0, resent_bytes = 0;
    std::uint64_t go_backs = 0;       // resends after acknowledgements stalled
    std::uint64_t base_restarts = 0;  // a new base_run seen (after the first)
};

class SendWindow {
  public:
    explicit SendWindow(SendConfig config = {}) : config_(config) {}

    // An acknowledgement: the base station (run `base_run`) holds every seq <= through.
    void on_ack(std::uint64_t through, std::uint64_t base_run, double now);
    // Acknowledgements come back after a silence long enough for DDS to have dropped the base
    // station's reader (its participant's lease): what was in flight is gone, send it again now
    // rather than after resend_after_s.
    void resume_after_silence(double now);
    // The seq to send now, given the seqs held [first_held, last_held] (first_held > last_held:
    // none); nullopt when everything held is sent or the window is full.
    std::optional<std::uint64_t> next(std::uint64_t first_held, std::uint64_t last_held,
                                      double now);
    // `seq` (returned by next()) went out, `bytes` long.
    void sent(std::uint64_t seq, std::uint64_t bytes, double now);

    std::uint64_t acked() const { return acked_; }
    std::uint64_t in_flight_bytes() const { return in_flight_bytes_; }
    bool heard_base() const { return base_run_ != 0; }
    const SendStats& stats() const { return stats_; }

  private:
    void go_back(double now);
    SendConfig config_;
    std::uint64_t acked_ = 0;     // every seq <= acked_ is at the base station
    std::uint64_t next_ = 1;      // the next seq to send
    std::uint64_t highest_ = 0;   // highest seq ever sent (resends below it count as resent)
    std::uint64_t base_run_ = 0;  // 0: no acknowledgement yet
    std::map<std::uint64_t, std::uint64_t> in_flight_;  // seq -> bytes, sent and unacknowledged
    std::uint64_t in_flight_bytes_ = 0;
    double stalled_since_ = 0.0;  // last ack progress (or go-back)
    double last_heard_ = 0.0;     // last acknowledgement
    double wait_s_ = 0.0;         // current go-back wait
    SendStats stats_;
};

}  // namespace ltm::link
