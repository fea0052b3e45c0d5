// The CPU pacer's arithmetic on made-up clocks (no real time: deterministic).
#include "common/core/cpu_pacer.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>
#include <utility>
#include <vector>

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

TEST(CpuPacer, PacersOfASharedBudgetTogetherKeepItsShare) {
    // Two workers (e.g. the maintenance and the mapping's clearing) of 5 s of work each in pieces
    // of 20 ms, one after the other on the wall clock, from one budget of 0.4 of a core: 10 s of
    // CPU in about 25 s, and in any 1 s window at most 0.4 + the 0.1 s burst + one piece.
    auto budget = std::make_shared<CpuBudget>(0.4, 0.1);
    CpuPacer a(budget), b(budget);
    EXPECT_TRUE(a.shared());
    double cpu_a = 0.0, cpu_b = 0.0, wall = 0.0;
    a.wait_after(cpu_a, wall);
    b.wait_after(cpu_b, wall);
    std::vector<std::pair<double, double>> work;  // (start, end) of every piece, wall time
    for (int i = 0; i < 500; ++i) {
        CpuPacer& p = i % 2 == 0 ? a : b;
        double& cpu = i % 2 == 0 ? cpu_a : cpu_b;
        work.emplace_back(wall, wall + 0.02);
        cpu += 0.02;
        wall += 0.02;
        const double wait = p.wait_after(cpu, wall);
        wall += wait;
        p.waited(wall);
    }
    EXPECT_NEAR(wall, 10.0 / 0.4, 0.1 / 0.4 + 0.05);
    double worst = 0.0;
    for (double t = 0.0; t < wall; t += 0.01) {
        double used = 0.0;
        for (const auto& [s, e] : work)
            used += std::max(0.0, std::min(e, t + 1.0) - std::max(s, t));
        worst = std::max(worst, used);
    }
    EXPECT_LE(worst, 0.4 + 0.1 + 0.02 + 1e-9);
    EXPECT_GT(worst, 0.4);
    EXPECT_NEAR(a.longest_piece_s(), 0.02, 1e-12);
}

TEST(CpuPacer, AGlobalQueryOnTheSharedBudgetMakesTheOthersWait) {
    // A piece that cannot be cut (a 0.3 s query) puts the budget in debt: the other worker waits
    // until the budget is repaid, so the two together still average the share.
    auto budget = std::make_shared<CpuBudget>(0.5, 0.1);
    CpuPacer query(budget), worker(budget);
    query.wait_after(0.0, 0.0);
    worker.wait_after(0.0, 0.0);
    // The bucket was full (0.1 s): the query's 0.3 s leave it 0.2 s in debt, 0.4 s at 0.5.
    EXPECT_NEAR(query.wait_after(0.3, 0.3), 0.4, 1e-9);
    EXPECT_NEAR(worker.wait_after(0.0, 0.3), 0.4, 1e-9);
    EXPECT_NEAR(worker.wait_after(0.0, 0.5), 0.2, 1e-9);
    EXPECT_NEAR(worker.wait_after(0.0, 0.7 + 1e-9), 0.0, 1e-9);
}

TEST(CpuPacer, APieceThatCannotBeCutWaitsForAFullBudget) {
    // The mapping's save (one piece of ~0.3 s) waits until the maintenance's work left the
    // shared budget full: nothing paced drew from it for burst / share seconds.
    auto budget = std::make_shared<CpuBudget>(0.4, 0.1);
    CpuPacer worker(budget), save(budget);
    worker.wait_after(0.0, 0.0);
    save.wait_after(0.0, 0.0);
    EXPECT_TRUE(save.budget_full(0.0));
    EXPECT_EQ(worker.wait_after(0.05, 0.05), 0.0);  // within the burst: no wait, but not full
    EXPECT_FALSE(save.budget_full(0.05));
    EXPECT_EQ(save.wait_now(0.05), 0.0);  // not in debt either
    EXPECT_FALSE(save.budget_full(0.05 + 0.03 / 0.4));
    EXPECT_TRUE(save.budget_full(0.05 + 0.05 / 0.4 + 1e-9));
}

TEST(CpuBudget, ANamedBudgetIsSharedWithTheSameShareOnly) {
    std::string error;
    EXPECT_EQ(shared_cpu_budget("test-b", 0.0, 0.1, &error), nullptr);
    EXPECT_EQ(error, "no CPU budget 'test-b' (a component that declares it sets its share)");
    auto first = shared_cpu_budget("test-b", 0.4, 0.1, &error);
    ASSERT_NE(first, nullptr);
    EXPECT_EQ(shared_cpu_budget("test-b", 0.4, 0.2, &error), first);
    EXPECT_EQ(shared_cpu_budget("test-b", 0.0, 0.2, &error), first);  // whatever it has
    EXPECT_EQ(shared_cpu_budget("test-b", 0.3, 0.1, &error), nullptr);
    EXPECT_EQ(error,
              "the CPU budget 'test-b' is 0.4 of a core (set by the first to declare it), "
              "not 0.3");
    EXPECT_NE(shared_cpu_budget("test-c", 0.3, 0.1, &error), first);
    first.reset();  // nobody holds it: the next one starts anew
    auto again = shared_cpu_budget("test-b", 0.3, 0.1, &error);
    ASSERT_NE(again, nullptr);
    EXPECT_DOUBLE_EQ(again->share(), 0.3);
}

}  // namespace
}  // namespace ltm::common
