#include "common/core/cpu_pacer.hpp"

#include <algorithm>

namespace ltm::common {

CpuPacer::CpuPacer(double share, double burst_s)
    : share_(std::clamp(share, 1e-3, 1.0)), burst_s_(std::max(0.0, burst_s)), tokens_(burst_s_) {}

void CpuPacer::fill(double wall_s) {
    tokens_ = std::min(burst_s_, tokens_ + share_ * std::max(0.0, wall_s - last_wall_));
    last_wall_ = std::max(last_wall_, wall_s);
}

double CpuPacer::wait_after(double cpu_s, double wall_s) {
    if (!started_) {  // the first report only sets the clocks
        started_ = true;
        last_cpu_ = cpu_s;
        last_wall_ = wall_s;
        return 0.0;
    }
    if (share_ >= 1.0) return 0.0;
    fill(wall_s);
    tokens_ -= std::max(0.0, cpu_s - last_cpu_);
    last_cpu_ = std::max(last_cpu_, cpu_s);
    return tokens_ >= 0.0 ? 0.0 : -tokens_ / share_;
}

void CpuPacer::waited(double wall_s) {
    if (started_) fill(wall_s);
}

}  // namespace ltm::common
