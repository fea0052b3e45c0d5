#include "registration/core/parallel.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <vector>

namespace ltm::registration {
namespace {

TEST(ParallelFor, VisitsEveryIndexOnceInFixedChunks) {
    for (const int threads : {1, 2, 3}) {
        ParallelFor parallel(threads);
        EXPECT_EQ(parallel.threads(), threads);
        const std::size_t n = 10007, grain = 256;
        std::vector<std::atomic<int>> seen(n);
        std::vector<int> chunk_of(n, -1);
        parallel.run(n, grain, [&](std::size_t c, std::size_t begin, std::size_t end) {
            EXPECT_EQ(begin, c * grain);
            EXPECT_EQ(end, std::min(n, (c + 1) * grain));
            for (std::size_t i = begin; i < end; ++i) {
                ++seen[i];
                chunk_of[i] = int(c);
            }
        });
        for (std::size_t i = 0; i < n; ++i) {
            ASSERT_EQ(seen[i].load(), 1) << i;
            ASSERT_EQ(chunk_of[i], int(i / grain));
        }
    }
    EXPECT_EQ(ParallelFor::chunk_count(0, 256), 0u);
    EXPECT_EQ(ParallelFor::chunk_count(257, 256), 2u);
}

}  // namespace
}  // namespace ltm::registration
