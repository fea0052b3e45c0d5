// The CPU pacer's arithmetic on made-up clocks (no real time: deterministic).
#include "common/core/cpu_pacer.hpp"

#include <gtest/gtest.h>

namespace ltm::common {
namespace {

// Work of `cpu` seconds a piece, each piece taking as long in wall time, then the pacer's wait:
// the CPU used over the whole run and the longest run of work with no wait.
struct Paced {
    double cpu = 0.0, wall = 0.0;
};
Paced run(CpuPacer& pacer, double piece, int pieces) {
    Paced r;
    pacer.wait_after(0.0, 0.0);  // starts the clocks
    for (int i = 0; i < pieces; ++i) {
        r.cpu += piece;
        r.wall += piece;
        const double wait = pacer.wait_after(r.cpu, r.wall);
        EXPECT_GE(wait, 0.0);
        r.wall += wait;
        pacer.waited(r.wall);
    }
    return r;
}

TEST(CpuPacer, AShareOfOneNeverWaits) {
    CpuPacer pacer(1.0, 0.1);
    const Paced r = run(pacer, 0.05, 100);
    EXPECT_DOUBLE_EQ(r.wall, r.cpu);
}

TEST(CpuPacer, LongWorkIsSpreadToItsShareOfACore) {
    // A 5 s pass in pieces of 50 ms at a third of a core: about 15 s of wall time, and no more
    // than the share plus the burst in any stretch.
    CpuPacer pacer(1.0 / 3.0, 0.1);
    const Paced r = run(pacer, 0.05, 100);
    EXPECT_NEAR(r.cpu, 5.0, 1e-9);
    EXPECT_GE(r.wall, 5.0 * 3.0 - 0.1 * 3.0 - 1e-9);
    EXPECT_LE(r.wall, 5.0 * 3.0 + 0.05 * 3.0 + 1e-9);
}

TEST(CpuPacer, WorkWithinItsShareDoesNotWait) {
    // 10 ms of work every 100 ms (idle between): a 10 % load under a 30 % share.
    CpuPacer pacer(0.3, 0.05);
    pacer.wait_after(0.0, 0.0);
    double cpu = 0.0, wall = 0.0;
    for (int i = 0; i < 50; ++i) {
        wall += 0.09;  // idle
        pacer.waited(wall);
        cpu += 0.01;
        wall += 0.01;
        EXPECT_EQ(pacer.wait_after(cpu, wall), 0.0) << i;
    }
    // A burst after idling: the bucket (0.05 s deep, full again) pays for the first 40 ms; the
    // next 40 ms get its last 10 ms and the share of their own 40 ms, the rest is waited for.
    cpu += 0.04;
    wall += 0.04;
    EXPECT_EQ(pacer.wait_after(cpu, wall), 0.0);
    cpu += 0.04;
    wall += 0.04;
    EXPECT_NEAR(pacer.wait_after(cpu, wall), (0.04 - 0.01 - 0.3 * 0.04) / 0.3, 1e-9);
}

}  // namespace
}  // namespace ltm::common
