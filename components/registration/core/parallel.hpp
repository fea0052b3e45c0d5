#pragma once
// Chunked parallel loops on an optional thread budget (TBB underneath). Owns no long-lived thread
// of its own: with threads == 1 the loop runs inline. Chunk boundaries depend only on n and the
// grain, so per-chunk partial results summed in chunk order are identical for any thread count.
#include <cstddef>
#include <functional>
#include <memory>

namespace ltm::registration {

class ParallelFor {
  public:
    explicit ParallelFor(int threads);
    ~ParallelFor();
    ParallelFor(const ParallelFor&) = delete;
    ParallelFor& operator=(const ParallelFor&) = delete;

    int threads() const { return threads_; }
    static std::size_t chunk_count(std::size_t n, std::size_t grain) {
        return grain == 0 ? 0 : (n + grain - 1) / grain;
    }
    // body(chunk, begin, end) for each chunk [chunk * grain, min(n, (chunk + 1) * grain)).
    void run(std::size_t n, std::size_t grain,
             const std::function<void(std::size_t, std::size_t, std::size_t)>& body);

  private:
    struct Arena;
    int threads_;
    std::unique_ptr<Arena> arena_;
};

}  // namespace ltm::registration
