#pragma once
// The base station's side of one robot run: packets arrive out of order, twice, or not at all
// (until resent); ReceiveWindow hands each one on exactly once, in seq order.
#include <cstddef>
#include <cstdint>
#include <map>
#include <vector>

#include "link/core/link_journal.hpp"

namespace ltm::link {

struct ReceiveStats {
    std::uint64_t received = 0;    // packets offered
    std::uint64_t duplicates = 0;  // already handed on, or already held
    std::uint64_t lost = 0;        // seqs skipped: the robot no longer holds them
    std::uint64_t overflow = 0;    // refused: too far ahead of the next seq (resent later)
};

class ReceiveWindow {
  public:
    // `through`: every seq <= through was handed on already (a restarted base station's journal).
    explicit ReceiveWindow(std::uint64_t through = 0, std::size_t max_held = 64)
        : through_(through), max_held_(max_held) {}

    // Offers a packet; `first_seq` is the oldest seq its sender still holds (seqs below it that
    // never arrived are lost for good and skipped). Returns what can now be handed on, in order.
    std::vector<JournalRecord> offer(JournalRecord record, std::uint64_t first_seq);

    std::uint64_t through() const { return through_; }
    std::size_t held() const { return held_.size(); }
    const ReceiveStats& stats() const { return stats_; }

  private:
    std::uint64_t through_;
    std::size_t max_held_;
    std::map<std::uint64_t, JournalRecord> held_;  // above through_ + 1, waiting for the gap
    ReceiveStats stats_;
};

}  // namespace ltm::link
