#pragma once
// What each component says it holds, by part ("local maps", "queue", ...), for the host's minute
// log line beside the process's resident and heap figures (issue 28 item 3: which part of a
// mission grows with the day). A component reports from any thread at its own pace
// (ComponentContext::report_memory); the host reads the last report of each part.
#include <cstddef>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

namespace ltm::runtime {

// How often a component reports (seconds): the host logs the reports once a minute.
inline constexpr double kMemoryReportPeriod = 10.0;

struct HeldPart {
    std::string part;
    std::size_t bytes = 0;
};

// One component's parts, in the order they were first reported. Thread-safe.
class HeldMemory {
  public:
    // The part's bytes now (replaces its last report).
    void set(const std::string& part, std::size_t bytes);
    std::vector<HeldPart> parts() const;

  private:
    mutable std::mutex mutex_;
    std::vector<HeldPart> parts_;
};

// "held: mapping 38 MB (local maps 28, keyframes 6, removed cells 4), maintenance 95 MB (...)":
// each component's total and, when it reported more than one part, its parts (MB, rounded).
// Components that reported nothing are left out; "" when none did.
std::string held_memory_text(
    const std::vector<std::pair<std::string, std::vector<HeldPart>>>& components);

}  // namespace ltm::runtime
