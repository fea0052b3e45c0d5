#include "runtime/held_memory.hpp"

#include <gtest/gtest.h>

#include <thread>

namespace ltm::runtime {
namespace {

TEST(HeldMemory, KeepsTheLastReportOfEachPartInTheOrderFirstReported) {
    HeldMemory held;
    held.set("local maps", 10);
    held.set("keyframes", 5);
    held.set("local maps", 28);
    const std::vector<HeldPart> parts = held.parts();
    ASSERT_EQ(parts.size(), 2u);
    EXPECT_EQ(parts[0].part, "local maps");
    EXPECT_EQ(parts[0].bytes, 28u);
    EXPECT_EQ(parts[1].part, "keyframes");
    EXPECT_EQ(parts[1].bytes, 5u);
}

TEST(HeldMemory, TakesReportsFromOtherThreads) {
    HeldMemory held;
    std::thread a([&] {
        for (std::size_t i = 0; i < 1000; ++i) held.set("a", i);
    });
    std::thread b([&] {
        for (std::size_t i = 0; i < 1000; ++i) held.set("b", 2 * i);
    });
    a.join();
    b.join();
    const std::vector<HeldPart> parts = held.parts();
    ASSERT_EQ(parts.size(), 2u);
    for (const HeldPart& p : parts) EXPECT_EQ(p.bytes, p.part == "a" ? 999u : 1998u);
}

TEST(HeldMemory, TheLineGivesEachComponentsTotalAndItsParts) {
    const std::string line = held_memory_text({
        {"mapping", {{"local maps", 28'400'000}, {"keyframes", 6'000'000}}},
        {"odometry", {}},
        {"maintenance", {{"map", 64'300'000}}},
    });
    EXPECT_EQ(line, "held: mapping 34 MB (local maps 28, keyframes 6), maintenance 64 MB");
    EXPECT_EQ(held_memory_text({{"odometry", {}}}), "");
}

}  // namespace
}  // namespace ltm::runtime
