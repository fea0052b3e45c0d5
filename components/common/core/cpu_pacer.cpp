#include "common/core/cpu_pacer.hpp"

#include <algorithm>
#include <utility>

namespace ltm::common {

CpuPacer::CpuPacer(double share, double burst_s)
    : budget_(std::make_shared<CpuBudget>(share, burst_s)) {}

CpuPacer::CpuPacer(std::shared_ptr<CpuBudget> budget) : budget_(std::move(budget)) {}

double CpuPacer::wait_after(double cpu_s, double wall_s) {
    if (!started_) {  // the first report only sets the clocks
        started_ = true;
        last_cpu_ = cpu_s;
        budget_->charge(0.0, wall_s);
        return 0.0;
    }
    const double piece = std::max(0.0, cpu_s - last_cpu_);
    longest_piece_s_ = std::max(longest_piece_s_, piece);
    last_cpu_ = std::max(last_cpu_, cpu_s);
    return budget_->charge(piece, wall_s);
}

double CpuPacer::wait_now(double wall_s) { return budget_->charge(0.0, wall_s); }

void CpuPacer::waited(double wall_s) {
    if (started_) budget_->charge(0.0, wall_s);
}

}  // namespace ltm::common
