#include "runtime/heap_trim.hpp"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace ltm::runtime {

HeapTrimmer::HeapTrimmer(double period_s, Clock::time_point start)
    : period_(std::chrono::duration_cast<Clock::duration>(
          std::chrono::duration<double>(period_s > 0 ? period_s : 0.0))),
      next_(start + period_),
      enabled_(period_s > 0) {}

bool HeapTrimmer::poll(Clock::time_point now) {
    if (!enabled_ || now < next_) return false;
    trim_heap();
    ++trims_;
    next_ = now + period_;
    return true;
}

bool trim_heap() {
#if defined(__GLIBC__)
    return malloc_trim(0) != 0;
#else
    return false;
#endif
}

}  // namespace ltm::runtime
