#pragma once
// The runtime host: one process, one DDS participant, the components of a launch config.
#include <atomic>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "runtime/component_runner.hpp"
#include "runtime/domain.hpp"
#include "runtime/launch_config.hpp"

namespace ltm::runtime {

class Host {
  public:
    // Creates the participant and configures every component. Throws ConfigError (one line:
    // file:line: key: problem) or DdsError; nothing runs before every component is configured.
    explicit Host(LaunchConfig config);
    ~Host();

    // Activates the components and runs until SIGINT/SIGTERM (which the caller must block in
    // every thread, see block_stop_signals), request_stop(), every source finished with all input
    // processed, the idle timeout, or a component failure under the `stop` policy. Then every
    // component is deactivated and shut down within the configured timeout.
    // Every output the components reported (a map, a recording, a mesh) is listed.
    // Returns the process exit code: 0 ("stopped cleanly": everything stopped within the
    // deadline and every output was saved), 1 (a component failed), 3 (a component did not stop
    // within the deadline: the process exits without waiting for it), 4 (an output could not be
    // saved; the log names it).
    int run();
    void request_stop() { stop_ = true; }

    std::size_t component_count() const { return runners_.size(); }
    double startup_ms() const { return startup_ms_; }

  private:
    bool all_drained();
    bool handle_failures(int& exit_code);
    // Stops every component in launch-config order within `budget` seconds; true when one did
    // not stop in time.
    bool stop_components(double budget);
    // Logs each component's outputs; false when one could not be saved.
    bool report_outputs() const;

    LaunchConfig config_;
    std::unique_ptr<Domain> domain_;
    std::vector<std::unique_ptr<ComponentRunner>> runners_;
    std::map<std::string, int> restarts_;
    std::atomic<bool> stop_{false};
    std::uint64_t last_dispatched_ = ~0ull;
    int drained_polls_ = 0;
    double startup_ms_ = 0;
};

// Blocks SIGINT and SIGTERM in the calling thread and every thread it starts afterwards, so that
// Host::run receives them synchronously. Call first thing in main().
void block_stop_signals();

// glibc malloc thresholds that keep large samples (1-2 MB scans) on the heap instead of fresh
// mmap()s: in-process transfer of a 1.4 MB sample drops from ~2 ms to ~0.2 ms. And at most one
// malloc arena a core (glibc's default is eight a core; MALLOC_ARENA_MAX in the environment wins):
// each component thread with an arena of its own kept freed memory there between two trims
// (heap_trim.hpp); with one arena a core a lifelong day's host peaked 45 MB lower (571 / 584
// against 628 / 619 MB, repeat_fortnight day 3, fast mode, the same CPU time;
// components/bench/lifelong/README.md, "Ten days").
void tune_malloc_for_large_samples();

}  // namespace ltm::runtime
