#pragma once
// A CPU budget that several threads draw from (issue 28: the robot's background work, i.e. the
// maintenance passes, the mapping's clearing of their cells and the localisation's global queries,
// together within what is left of one core beside the odometry and the tracking, which are never
// paced). The token bucket of cpu_pacer.hpp, shared and thread-safe: filled at `share` of one core
// while wall time passes, at most `burst_s` deep; every thread's work is charged to it, and a
// thread that finds it in debt waits (cpu_pacer.hpp) until it is back to zero. So over any window
// of W seconds all of them together use at most share * W + burst_s of CPU, plus the pieces that
// were running when the budget ran out (a piece is not interrupted: the callers keep them short).
// Pure arithmetic on the times it is given; the callers read the clocks and wait.
#include <memory>
#include <mutex>
#include <string>

namespace ltm::common {

class CpuBudget {
  public:
    // share in (0, 1] of one core (1: never in debt), burst_s >= 0 [s of CPU].
    CpuBudget(double share, double burst_s);

    // cpu_s [s] of work done, charged at the wall time wall_s [s, any origin, non-decreasing]:
    // the wait [s] until the budget is back to zero, 0 when it is not in debt. The first call
    // (any caller) starts the budget's clock.
    double charge(double cpu_s, double wall_s);

    // The CPU [s] it holds at wall_s (negative: in debt), nothing charged.
    double tokens(double wall_s);

    double share() const { return share_; }
    double burst_s() const { return burst_s_; }

  private:
    void fill_locked(double wall_s);

    const double share_, burst_s_;
    std::mutex mutex_;
    bool started_ = false;
    double tokens_ = 0.0, last_wall_ = 0.0;
};

// The process's budget called `name`, shared by every caller that names it while one of them
// holds it: the first creates it with its share and burst; a later caller must give the same
// share (0: whatever it has), else nullptr and `error` says why in one line. share 0 for a budget
// that does not exist yet: nullptr and the error.
std::shared_ptr<CpuBudget> shared_cpu_budget(const std::string& name, double share, double burst_s,
                                             std::string* error);

}  // namespace ltm::common
