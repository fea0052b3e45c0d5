#pragma once
// Progress of a long run on stderr: done/total, rate and ETA, at most once a second.
#include <chrono>
#include <cstddef>
#include <string>

namespace ltm::common {

class Progress {
  public:
    // total == 0: unknown length (no percentage, no ETA).
    Progress(std::string label, std::size_t total, std::string unit = "frames");
    // Reports `done` items finished; prints when a second has passed since the last line.
    void update(std::size_t done);
    // Prints the final line (always).
    void finish();
    double rate() const;  // items per second so far

  private:
    void print(bool final_line);
    std::string label_, unit_;
    std::size_t total_, done_ = 0;
    std::chrono::steady_clock::time_point start_, last_print_;
};

}  // namespace ltm::common
