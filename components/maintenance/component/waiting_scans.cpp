#include "maintenance/component/waiting_scans.hpp"

#include <algorithm>

namespace ltm::maintenance {

WaitingScans::WaitingScans(std::size_t max_scans, std::size_t max_bytes)
    : max_scans_(max_scans), max_bytes_(max_bytes) {}

void WaitingScans::add(std::size_t bytes, std::size_t unpacked_bytes) {
    items_.emplace_back(bytes, unpacked_bytes);
    bytes_ += bytes;
    unpacked_ += unpacked_bytes;
    if (bytes_ > peak_bytes_) {
        peak_bytes_ = bytes_;
        peak_unpacked_ = unpacked_;
    }
    peak_count_ = std::max(peak_count_, items_.size());
}

void WaitingScans::remove_front() {
    if (items_.empty()) return;
    const auto item = items_.front();
    items_.pop_front();
    removed(item);
}

void WaitingScans::remove_back() {
    if (items_.empty()) return;
    const auto item = items_.back();
    items_.pop_back();
    removed(item);
}

void WaitingScans::removed(const std::pair<std::size_t, std::size_t>& item) {
    bytes_ -= item.first;
    unpacked_ -= item.second;
    if (items_.size() <= max_scans_ / 2 && (max_bytes_ == 0 || bytes_ <= max_bytes_ / 2))
        full_ = false;  // room again: the next time it fills is news
}

bool WaitingScans::over_bytes(std::size_t bytes) const {
    return max_bytes_ > 0 && !items_.empty() && bytes_ + bytes > max_bytes_;
}

bool WaitingScans::mark_full() {
    if (full_) return false;
    full_ = true;
    ++full_times_;
    return true;
}

}  // namespace ltm::maintenance
