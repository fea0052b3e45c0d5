#pragma once
// A bound on the CPU share of long work (issue 28: maintenance passes and the mapping's edits
// spread, not bursts): a token bucket of CPU time (cpu_budget.hpp), filled at `share` of one core
// while wall time passes, at most `burst_s` deep; its own, or one that other threads' pacers draw
// from too (a shared budget: their work together within its share). After each piece of work the
// caller reports its CPU clock and the wall time; the answer is how long to wait before the next
// piece so that, over any window of W seconds, the work used at most share * W + burst_s of CPU
// plus the piece running when the bucket ran out (the pacer cannot cut a piece: the longest one
// is kept, longest_piece_s, for the log). Pure arithmetic (no clock, no thread): the component
// reads the clocks and waits.
#include <memory>

#include "common/core/cpu_budget.hpp"

namespace ltm::common {

class CpuPacer {
  public:
    // A budget of its own. share in (0, 1]: 1 never waits.
    CpuPacer(double share, double burst_s);
    // Drawing from a budget shared with other pacers (not null).
    explicit CpuPacer(std::shared_ptr<CpuBudget> budget);

    // After a piece of work: this pacer's CPU clock (e.g. its thread's CPU time) and the wall
    // time now [s] (any origin, each non-decreasing). Returns the wait before the next piece [s],
    // 0 when within the budget. The first call only starts the clocks (call it before the first
    // piece).
    double wait_after(double cpu_s, double wall_s);
    // The wait happened (or not): the wall time now [s].
    void waited(double wall_s);
    // The wait the budget asks for now, nothing charged (0: free to start a piece). Starts the
    // clocks as wait_after's first call when it comes first.
    double wait_now(double wall_s);

    // The budget full at wall_s: no work drew from it for a while (a piece that cannot be cut,
    // a save say, waits for this, so that it does not add to the others' in the same second).
    bool budget_full(double wall_s) const {
        return budget_->tokens(wall_s) >= budget_->burst_s() - 1e-9;
    }

    double share() const { return budget_->share(); }
    bool shared() const { return budget_.use_count() > 1; }
    // The most CPU between two wait_after calls so far [s]: what can pass the share in a window.
    double longest_piece_s() const { return longest_piece_s_; }

  private:
    std::shared_ptr<CpuBudget> budget_;
    bool started_ = false;
    double last_cpu_ = 0.0, longest_piece_s_ = 0.0;
};

}  // namespace ltm::common
