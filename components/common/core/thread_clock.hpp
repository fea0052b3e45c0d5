#pragma once
// The two clocks a paced worker reads (cpu_pacer.hpp): this thread's CPU time, which the machine's
// load does not inflate, and a steady wall clock. Seconds, any origin.
#include <time.h>

#include <chrono>

namespace ltm::common {

inline double thread_cpu_s() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

inline double steady_wall_s() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

}  // namespace ltm::common
