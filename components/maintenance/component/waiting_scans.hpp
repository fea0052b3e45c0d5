#pragma once
// The maintenance worker's queue as memory (issue 28): the scans waiting for the worker, in queue
// order, each with its bytes as it waits (packed or not) and unpacked; their peak; the bounds
// (max_queue scans, max_queue_mb bytes) and whether the queue is full since it last had room, so
// that a full queue is logged once, not once a scan, and never silently. Not thread-safe: the
// component holds its mutex.
#include <cstddef>
#include <cstdint>
#include <deque>
#include <utility>

namespace ltm::maintenance {

class WaitingScans {
  public:
    // max_bytes 0: no bound but the count.
    WaitingScans(std::size_t max_scans, std::size_t max_bytes);

    void add(std::size_t bytes, std::size_t unpacked_bytes);
    // The oldest (the worker took it, or it was dropped) or the newest (refused) left.
    void remove_front();
    void remove_back();

    // A scan of `bytes` would take the waiting ones past max_bytes (never when none waits).
    bool over_bytes(std::size_t bytes) const;
    // The queue was found full (by either bound): true the first time since it last had room,
    // i.e. since it went down to half of both bounds.
    bool mark_full();

    std::size_t count() const { return items_.size(); }
    std::size_t bytes() const { return bytes_; }
    std::size_t peak_count() const { return peak_count_; }
    std::size_t peak_bytes() const { return peak_bytes_; }
    std::size_t peak_unpacked_bytes() const { return peak_unpacked_; }
    std::uint64_t full_times() const { return full_times_; }

  private:
    void removed(const std::pair<std::size_t, std::size_t>& item);

    std::size_t max_scans_, max_bytes_;
    std::deque<std::pair<std::size_t, std::size_t>> items_;  // (bytes, unpacked)
    std::size_t bytes_ = 0, unpacked_ = 0;
    std::size_t peak_count_ = 0, peak_bytes_ = 0, peak_unpacked_ = 0;
    bool full_ = false;
    std::uint64_t full_times_ = 0;
};

}  // namespace ltm::maintenance
