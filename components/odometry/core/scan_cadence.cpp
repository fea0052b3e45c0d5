// ScanCadence: the median of the last intervals between scans.
#include "odometry/core/scan_cadence.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace ltm::odometry {

void ScanCadence::add(double interval) {
    if (!std::isfinite(interval) || interval <= 0.0) return;
    intervals_.push_back(interval);
    if (intervals_.size() > kWindow) intervals_.pop_front();
}

double ScanCadence::usual() const {
    if (intervals_.empty()) return 0.0;
    std::vector<double> v(intervals_.begin(), intervals_.end());
    const auto mid = v.begin() + std::ptrdiff_t(v.size() / 2);
    std::nth_element(v.begin(), mid, v.end());
    return *mid;
}

bool ScanCadence::is_break(double interval, double gap, double factor) const {
    if (gap <= 0.0 || !(interval > gap)) return false;
    if (factor <= 0.0) return true;
    return known() && interval > factor * usual();
}

}  // namespace ltm::odometry
