// HeapTrimmer: trims once a period, never when off; trim_heap() gives freed pages back.
#include "runtime/heap_trim.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <memory>
#include <vector>

namespace ltm::runtime {
namespace {

using Clock = HeapTrimmer::Clock;
using std::chrono::milliseconds;

TEST(HeapTrimmer, TrimsOnceAPeriod) {
    const Clock::time_point t0{};
    HeapTrimmer t(10.0, t0);
    EXPECT_FALSE(t.poll(t0));
    EXPECT_FALSE(t.poll(t0 + milliseconds(9999)));
    EXPECT_TRUE(t.poll(t0 + milliseconds(10000)));
    EXPECT_FALSE(t.poll(t0 + milliseconds(15000)));  // the next period starts at the trim
    EXPECT_TRUE(t.poll(t0 + milliseconds(20000)));
    EXPECT_EQ(t.trims(), 2u);
}

TEST(HeapTrimmer, OffNeverTrims) {
    const Clock::time_point t0{};
    HeapTrimmer t(0.0, t0);
    EXPECT_FALSE(t.poll(t0 + std::chrono::hours(1)));
    EXPECT_EQ(t.trims(), 0u);
}

// Resident pages of this process (/proc/self/statm), or 0 when unknown.
long resident_pages() {
    std::FILE* f = std::fopen("/proc/self/statm", "r");
    if (!f) return 0;
    long size = 0, resident = 0;
    const int n = std::fscanf(f, "%ld %ld", &size, &resident);
    std::fclose(f);
    return n == 2 ? resident : 0;
}

#if defined(__GLIBC__)
TEST(TrimHeap, GivesFreedPagesBack) {
    if (resident_pages() == 0) GTEST_SKIP() << "no /proc/self/statm";
    // 64 MiB in 4 KiB blocks, written, then freed but for the last one, which keeps the arena's
    // top in use (so free() alone gives nothing back).
    std::vector<std::unique_ptr<char[]>> blocks(16384);
    for (auto& b : blocks) {
        b.reset(new char[4096]);
        std::memset(b.get(), 1, 4096);
    }
    for (std::size_t i = 0; i + 1 < blocks.size(); ++i) blocks[i].reset();
    const long before = resident_pages();
    trim_heap();
    const long after = resident_pages();
    const long page_kib = sysconf(_SC_PAGESIZE) / 1024;
    EXPECT_GT((before - after) * page_kib, 32 * 1024)  // most of the 64 MiB
        << "resident " << before * page_kib << " KiB before, " << after * page_kib << " after";
}
#endif

#if defined(__GLIBC__)
TEST(HeapStats, CountsWhatTheProgramHoldsAndWhatMallocKeepsFree) {
    const HeapStats before = heap_stats();
    if (!before.known) GTEST_SKIP() << "no mallinfo2 in this C library";
    std::vector<std::unique_ptr<char[]>> blocks(4096);  // 16 MiB in 4 KiB blocks, written
    for (auto& b : blocks) {
        b.reset(new char[4096]);
        std::memset(b.get(), 1, 4096);
    }
    const HeapStats held = heap_stats();
    EXPECT_GE(held.in_use, before.in_use + 15 * 1024 * 1024);
    EXPECT_GE(held.held, held.in_use);
    EXPECT_GE(held.peak, held.resident);
    EXPECT_GT(held.resident, std::size_t(16) * 1024 * 1024);
    for (auto& b : blocks) b.reset();
    const HeapStats freed = heap_stats();
    EXPECT_LE(freed.in_use + 15 * 1024 * 1024, held.in_use);
    const std::string line = heap_stats_text(held);
    EXPECT_NE(line.find("in use of"), std::string::npos) << line;
    EXPECT_NE(line.find("resident "), std::string::npos) << line;
}
#endif

}  // namespace
}  // namespace ltm::runtime
