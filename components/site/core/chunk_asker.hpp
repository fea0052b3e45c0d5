#pragma once
// Which chunks the robot asks the base station for, and when (site_sync, issue 26). At most
// `window` chunks are asked and not yet received at a time (what is in flight on the link); while
// chunks keep arriving DDS repairs losses itself, so a chunk is asked again only when nothing
// arrived for `resend_after_s` (a base station that restarted, an outage longer than DDS's lease,
// requests or chunks dropped from a history): then everything outstanding is asked again.
#include <cstddef>
#include <set>
#include <vector>

#include "site/core/version_files.hpp"

namespace ltm::site_sync {

class ChunkAsker {
  public:
    ChunkAsker(std::size_t window, double resend_after_s);
    // The chunks to ask for now, from the ones still missing (in the order to be sent).
    std::vector<ChunkRef> due(const std::vector<ChunkRef>& missing, double now_s);
    void received(ChunkRef c, double now_s);
    void reset();  // a new offer
    std::size_t outstanding() const { return outstanding_.size(); }
    std::size_t asked_again() const { return asked_again_; }  // chunks asked more than once

  private:
    std::size_t window_;
    double resend_after_s_;
    std::set<ChunkRef> outstanding_;
    double last_progress_s_ = -1;
    std::size_t asked_again_ = 0;
};

}  // namespace ltm::site_sync
