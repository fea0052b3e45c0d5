#include "common/core/cpu_budget.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

namespace ltm::common {

CpuBudget::CpuBudget(double share, double burst_s)
    : share_(std::clamp(share, 1e-3, 1.0)), burst_s_(std::max(0.0, burst_s)), tokens_(burst_s_) {}

void CpuBudget::fill_locked(double wall_s) {
    if (!started_) {
        started_ = true;
        last_wall_ = wall_s;
    }
    tokens_ = std::min(burst_s_, tokens_ + share_ * std::max(0.0, wall_s - last_wall_));
    last_wall_ = std::max(last_wall_, wall_s);
}

double CpuBudget::tokens(double wall_s) {
    std::lock_guard<std::mutex> lock(mutex_);
    fill_locked(wall_s);
    return share_ >= 1.0 ? burst_s_ : tokens_;
}

double CpuBudget::charge(double cpu_s, double wall_s) {
    std::lock_guard<std::mutex> lock(mutex_);
    fill_locked(wall_s);
    if (share_ >= 1.0) return 0.0;
    tokens_ -= std::max(0.0, cpu_s);
    return tokens_ >= 0.0 ? 0.0 : -tokens_ / share_;
}

std::shared_ptr<CpuBudget> shared_cpu_budget(const std::string& name, double share, double burst_s,
                                             std::string* error) {
    static std::mutex mutex;
    static std::map<std::string, std::weak_ptr<CpuBudget>> budgets;
    std::lock_guard<std::mutex> lock(mutex);
    std::shared_ptr<CpuBudget> b = budgets[name].lock();
    char text[160];
    if (!b) {
        if (!(share > 0.0 && share <= 1.0)) {
            std::snprintf(text, sizeof text,
                          "no CPU budget '%s' (a component that declares it sets its share)",
                          name.c_str());
            if (error) *error = text;
            return nullptr;
        }
        b = std::make_shared<CpuBudget>(share, burst_s);
        budgets[name] = b;
        return b;
    }
    if (share > 0.0 && std::abs(share - b->share()) > 1e-9) {
        std::snprintf(text, sizeof text,
                      "the CPU budget '%s' is %.3g of a core (set by the first to declare it), "
                      "not %.3g",
                      name.c_str(), b->share(), share);
        if (error) *error = text;
        return nullptr;
    }
    return b;
}

}  // namespace ltm::common
