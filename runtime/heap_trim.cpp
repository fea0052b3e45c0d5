#include "runtime/heap_trim.hpp"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include <cstdio>
#include <cstring>

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

namespace {

// VmRSS and VmHWM of this process in bytes (/proc/self/status), 0 when unknown.
void read_resident(std::size_t& resident, std::size_t& peak) {
    std::FILE* f = std::fopen("/proc/self/status", "r");
    if (!f) return;
    char line[256];
    while (std::fgets(line, sizeof line, f)) {
        unsigned long kib = 0;
        if (std::strncmp(line, "VmRSS:", 6) == 0 && std::sscanf(line + 6, "%lu", &kib) == 1)
            resident = std::size_t(kib) * 1024;
        else if (std::strncmp(line, "VmHWM:", 6) == 0 && std::sscanf(line + 6, "%lu", &kib) == 1)
            peak = std::size_t(kib) * 1024;
    }
    std::fclose(f);
}

std::string megabytes(std::size_t bytes) {
    return std::to_string((bytes + 500'000) / 1'000'000) + " MB";
}

}  // namespace

HeapStats heap_stats() {
    HeapStats s;
    read_resident(s.resident, s.peak);
#if defined(__GLIBC__) && (__GLIBC__ > 2 || (__GLIBC__ == 2 && __GLIBC_MINOR__ >= 33))
    const struct mallinfo2 m = mallinfo2();
    s.known = true;
    s.held = m.arena + m.hblkhd;
    s.in_use = m.uordblks + m.hblkhd;
#endif
    return s;
}

std::string heap_stats_text(const HeapStats& s) {
    std::string t = "resident " + (s.resident ? megabytes(s.resident) : std::string("unknown"));
    if (s.peak) t += " (peak " + megabytes(s.peak) + ")";
    if (s.known) t += ", heap " + megabytes(s.in_use) + " in use of " + megabytes(s.held) + " held";
    return t;
}

}  // namespace ltm::runtime
