#pragma once
// A site's newer versions, followed while a session runs (issue 26, the split robot): on the
// robot, the site_receiver commits the base station's next version into the robot's site while
// the localisation runs on an older one (or on none). newer() looks at SITE/versions/ and returns
// the newest intact version above the one in use; the caller loads it and says so with adopt().
// Only versions newer than the one in use are checked (map/core/site_check: every byte read
// once), and a damaged one only once (noted, then passed over: the receiver never commits a
// damaged version, so one is damaged on the disk and stays so). No DDS, no threads: the
// localisation component calls it from a thread of its own.
#include <cstdint>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "map/core/site_store.hpp"

namespace ltm::localisation {

class SiteFollower {
  public:
    // `in_use`: the number of the version the session runs on (0: none, a new site).
    SiteFollower(std::string site_dir, std::uint32_t in_use);

    // The newest intact version above the one in use, if one appeared. Damaged ones found on the
    // way are described in *notes (once each).
    std::optional<map::SiteVersion> newer(std::vector<std::string>* notes = nullptr);
    // The session now runs on version `number`.
    void adopt(std::uint32_t number) { in_use_ = number; }
    std::uint32_t in_use() const { return in_use_; }
    const std::string& site_dir() const { return site_dir_; }

  private:
    std::string site_dir_;
    std::uint32_t in_use_ = 0;
    std::set<std::uint32_t> damaged_;  // checked and found damaged: not checked again
};

}  // namespace ltm::localisation
