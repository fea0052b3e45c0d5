#include "link/core/receive_window.hpp"

namespace ltm::link {

std::vector<JournalRecord> ReceiveWindow::offer(JournalRecord record, std::uint64_t first_seq) {
    ++stats_.received;
    std::vector<JournalRecord> out;
    // Seqs the sender dropped before they arrived here will never come.
    if (first_seq > through_ + 1) {
        std::uint64_t skipped = first_seq - 1 - through_;
        for (auto it = held_.begin(); it != held_.end() && it->first < first_seq;) {
            --skipped;
            out.push_back(std::move(it->second));
            it = held_.erase(it);
        }
        stats_.lost += skipped;
        through_ = first_seq - 1;
    }
    const std::uint64_t seq = record.seq;
    if (seq <= through_ || held_.count(seq)) {
        ++stats_.duplicates;
    } else if (seq > through_ + 1 && held_.size() >= max_held_) {
        ++stats_.overflow;
    } else {
        held_.emplace(seq, std::move(record));
    }
    while (!held_.empty() && held_.begin()->first == through_ + 1) {
        out.push_back(std::move(held_.begin()->second));
        held_.erase(held_.begin());
        ++through_;
    }
    return out;
}

}  // namespace ltm::link
