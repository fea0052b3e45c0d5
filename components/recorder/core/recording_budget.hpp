#pragma once
// A folder of recordings kept within a size and a count (issue 28, item 4): the oldest whole
// files go first (by modification time), never a file being written. Used by the recorder
// component at start and while it records; no DDS, no threads.
#include <cstddef>
#include <cstdint>
#include <set>
#include <string>
#include <vector>

namespace ltm::recorder {

struct RecordingBudget {
    std::uint64_t max_total_bytes = 0;  // every matching file under the folder; 0: no bound
    std::size_t keep_newest = 0;        // at most this many files; 0: no bound
    std::string extension = ".mcap";    // which files count (searched in sub-folders too)
};

struct BudgetResult {
    std::vector<std::string> removed;  // oldest first
    std::uint64_t removed_bytes = 0;
    std::uint64_t kept_bytes = 0;  // what matches after the removals (protected files included)
    std::size_t kept_files = 0;
    // The protected files alone are over max_total_bytes (nothing else is left to remove).
    bool protected_over_budget = false;
    std::string error;  // one line when a file could not be listed or removed ("" otherwise)
};

// Removes the oldest matching files under `dir` (recursively, symbolic links not followed) until
// both bounds hold; the files in `protect` (being written) count but are never removed. A missing
// folder is an empty one.
BudgetResult enforce_budget(const std::string& dir, const RecordingBudget& budget,
                            const std::set<std::string>& protect);

// One line: "removed 3 recordings (412 MiB, oldest first: a.mcap, ...); 2 kept, 180 MiB".
std::string describe(const BudgetResult& result);

}  // namespace ltm::recorder
