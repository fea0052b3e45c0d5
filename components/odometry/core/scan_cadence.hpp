#pragma once
// The scan stream's cadence: its usual interval between scans (the median of the last few), so
// that a gap in the stream is judged against the stream itself. A LiDAR driver's stream (10 Hz)
// that stops for 2 s has a gap (the robot may have been carried); a keyframe stream (a scan every
// metre of travel: hku-avia's intervals 0.1-3 s, a 7 s pause where the walker stood still) does
// not break when the robot stands.
#include <cstddef>
#include <deque>

namespace ltm::odometry {

class ScanCadence {
  public:
    static constexpr std::size_t kWindow = 10;       // intervals kept
    static constexpr std::size_t kMinIntervals = 3;  // before that the cadence is unknown

    // The interval between two consecutive scans [s] (non-finite or non-positive: ignored).
    void add(double interval);
    bool known() const { return intervals_.size() >= kMinIntervals; }
    // The median of the kept intervals [s]; 0 while none.
    double usual() const;
    // A break in the stream: longer than `gap` [s] and, when `factor` > 0, longer than `factor`
    // times the usual interval, which must be known by then (the first intervals of a run are
    // never a break: nothing says what the stream's normal is). `gap` <= 0: never.
    bool is_break(double interval, double gap, double factor) const;

  private:
    std::deque<double> intervals_;
};

}  // namespace ltm::odometry
