#pragma once
// A bound on the CPU share of long work (issue 28: maintenance passes and the mapping's edits
// spread, not bursts): a token bucket of CPU time, filled at `share` of one core while wall time
// passes, at most `burst_s` deep. After each piece of work the caller reports its thread's CPU time
// and the wall time; the answer is how long to wait before the next piece so that, over any window
// of W seconds, the work used at most share * W + burst_s of CPU. Pure arithmetic (no clock, no
// thread): the component reads the clocks and waits.
namespace ltm::common {

class CpuPacer {
  public:
    // share in (0, 1]: 1 never waits.
    CpuPacer(double share, double burst_s);

    // After a piece of work: the thread's CPU time and the wall time now [s] (any origin, each
    // non-decreasing). Returns the wait before the next piece [s], 0 when within the budget. The
    // first call only starts the clocks (call it before the first piece).
    double wait_after(double cpu_s, double wall_s);
    // The wait happened (or not): the wall time now [s].
    void waited(double wall_s);

    double share() const { return share_; }

  private:
    void fill(double wall_s);

    double share_, burst_s_;
    bool started_ = false;
    double tokens_ = 0.0, last_cpu_ = 0.0, last_wall_ = 0.0;
};

}  // namespace ltm::common
