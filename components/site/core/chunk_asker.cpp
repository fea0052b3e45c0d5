#include "site/core/chunk_asker.hpp"

namespace ltm::site_sync {

ChunkAsker::ChunkAsker(std::size_t window, double resend_after_s)
    : window_(window == 0 ? 1 : window), resend_after_s_(resend_after_s) {}

std::vector<ChunkRef> ChunkAsker::due(const std::vector<ChunkRef>& missing, double now_s) {
    std::vector<ChunkRef> out;
    if (last_progress_s_ < 0) last_progress_s_ = now_s;
    if (!outstanding_.empty() && now_s - last_progress_s_ >= resend_after_s_) {
        asked_again_ += outstanding_.size();
        outstanding_.clear();  // stalled: ask again
        last_progress_s_ = now_s;
    }
    // Asked chunks that are no longer missing (stored by a resume) leave the window.
    std::set<ChunkRef> still;
    for (const ChunkRef& c : missing)
        if (outstanding_.count(c)) still.insert(c);
    outstanding_.swap(still);
    for (const ChunkRef& c : missing) {
        if (outstanding_.size() >= window_) break;
        if (outstanding_.insert(c).second) out.push_back(c);
    }
    return out;
}

void ChunkAsker::received(ChunkRef c, double now_s) {
    outstanding_.erase(c);
    last_progress_s_ = now_s;
}

void ChunkAsker::reset() {
    outstanding_.clear();
    last_progress_s_ = -1;
}

}  // namespace ltm::site_sync
