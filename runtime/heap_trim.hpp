#pragma once
// Gives the heap's free pages back to the system now and then (glibc malloc_trim(0)), so a
// host's resident memory follows what its components hold (issue 28 item 3).
//
// tune_malloc_for_large_samples() keeps scans on the heap (no mmap per sample) and lets each
// malloc arena keep up to 256 MiB free at its top; with a dozen component threads, each with an
// arena, the freed scans, range images and map snapshots left 31 % of what malloc held free
// (site_loop day 0 after 1900 scans: 552 MB held, 380 MB in use); one malloc_trim(0) returned
// 108 MB of the host's 633 MB (components/bench/budget/README.md, "Memory"). Trimming keeps the
// thresholds' speed: a page is given back only when no allocation uses it, and reused pages are
// faulted in again (at a period of seconds, well under 1 % of a core).
#include <chrono>
#include <cstddef>
#include <string>

namespace ltm::runtime {

class HeapTrimmer {
  public:
    using Clock = std::chrono::steady_clock;
    // `period_s` <= 0: never trims.
    explicit HeapTrimmer(double period_s, Clock::time_point start = Clock::now());

    // Trims when a period has passed since the last trim (or the start); true when it did.
    bool poll(Clock::time_point now = Clock::now());
    std::size_t trims() const { return trims_; }

  private:
    Clock::duration period_;
    Clock::time_point next_;
    bool enabled_;
    std::size_t trims_ = 0;
};

// Gives every malloc arena's free pages back to the system now; true when some memory was
// released (glibc), false otherwise or where malloc_trim does not exist.
bool trim_heap();

// What the process's memory is made of, in bytes: resident (VmRSS, and its peak VmHWM), what
// malloc's arenas hold from the system (heap pages and large mmapped blocks) and how much of that
// the program uses (glibc mallinfo2, summed over every arena). `known` is false where they cannot
// be read; then resident is still filled when /proc is there. held - in_use is what malloc keeps
// free: after a trim only the part in pages it cannot give back (a page with one live allocation on
// it).
struct HeapStats {
    bool known = false;
    std::size_t resident = 0;
    std::size_t peak = 0;  // VmHWM
    std::size_t held = 0;
    std::size_t in_use = 0;
};
HeapStats heap_stats();

// One line for a log: "resident 512 MB (peak 540 MB), heap 430 MB in use of 470 MB held".
std::string heap_stats_text(const HeapStats& s);

}  // namespace ltm::runtime
