#pragma once
// A journal's disk that refuses writes (full, read-only) is said in ONE line when it starts and
// one when it takes writes again; the refusals in between are counted, not repeated (a full disk
// under 10 Hz of keyframes would otherwise print ten lines a second).
#include <cstdint>
#include <string>

namespace ltm::link {

class WriteFault {
  public:
    // A refused write. Returns the line to log when it starts a spell of refusals, else "".
    std::string refused(const std::string& what) {
        ++count_;
        if (failing_) return "";
        failing_ = true;
        return what + " (further refusals are counted, not repeated)";
    }
    // A write that worked. Returns the line to log when it ends a spell of refusals, else "".
    std::string accepted(const std::string& what) {
        if (!failing_) return "";
        failing_ = false;
        const std::string line = what + " after " + std::to_string(count_ - reported_) +
                                 " refused write" + (count_ - reported_ == 1 ? "" : "s");
        reported_ = count_;
        return line;
    }
    bool failing() const { return failing_; }
    std::uint64_t total() const { return count_; }

  private:
    bool failing_ = false;
    std::uint64_t count_ = 0, reported_ = 0;
};

}  // namespace ltm::link
