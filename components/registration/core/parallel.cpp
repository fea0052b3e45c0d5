#include "registration/core/parallel.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>

namespace ltm::registration {

struct ParallelFor::Arena {
    explicit Arena(int threads) : arena(threads) {}
    tbb::task_arena arena;
};

ParallelFor::ParallelFor(int threads) : threads_(std::max(1, threads)) {
    if (threads_ > 1) arena_ = std::make_unique<Arena>(threads_);
}

ParallelFor::~ParallelFor() = default;

void ParallelFor::run(std::size_t n, std::size_t grain,
                      const std::function<void(std::size_t, std::size_t, std::size_t)>& body) {
    const std::size_t chunks = chunk_count(n, grain);
    if (chunks == 0) return;
    auto one = [&](std::size_t c) { body(c, c * grain, std::min(n, (c + 1) * grain)); };
    if (!arena_ || chunks == 1) {
        for (std::size_t c = 0; c < chunks; ++c) one(c);
        return;
    }
    arena_->arena.execute([&] {
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, chunks, 1),
                          [&](const tbb::blocked_range<std::size_t>& r) {
                              for (std::size_t c = r.begin(); c != r.end(); ++c) one(c);
                          });
    });
}

}  // namespace ltm::registration
