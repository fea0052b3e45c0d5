#include "common/core/progress.hpp"

#include <unistd.h>

#include <cstdio>

namespace ltm::common {

Progress::Progress(std::string label, std::size_t total, std::string unit)
    : label_(std::move(label)), unit_(std::move(unit)), total_(total) {
    start_ = last_print_ = std::chrono::steady_clock::now();
}

double Progress::rate() const {
    const double s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    return s > 0 ? done_ / s : 0.0;
}

void Progress::update(std::size_t done) {
    done_ = done;
    const auto now = std::chrono::steady_clock::now();
    if (now - last_print_ < std::chrono::seconds(1)) return;
    last_print_ = now;
    print(false);
}

void Progress::finish() { print(true); }

void Progress::print(bool final_line) {
    const double r = rate();
    char eta[32] = "";
    if (total_ > 0 && r > 0 && done_ <= total_ && !final_line) {
        const long s = static_cast<long>((total_ - done_) / r);
        std::snprintf(eta, sizeof eta, ", ETA %ldm%02lds", s / 60, s % 60);
    }
    char pct[32] = "";
    if (total_ > 0)
        std::snprintf(pct, sizeof pct, "/%zu (%.1f %%)", total_, 100.0 * done_ / total_);
    // On a terminal, rewrite one line; in logs, one line per report.
    const bool tty = isatty(fileno(stderr));
    std::fprintf(stderr, "%s%s: %zu%s %s, %.1f %s/s%s%s", tty ? "\r" : "", label_.c_str(), done_,
                 pct, unit_.c_str(), r, unit_.c_str(), eta, (final_line || !tty) ? "\n" : "");
    std::fflush(stderr);
}

}  // namespace ltm::common
