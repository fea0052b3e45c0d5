#pragma once
// What of a robot's link packets the base station's site already holds (issue 28, item 4): the
// record (map/core/link_applied.hpp) of the version a session starts from, and of each version
// committed while it runs. The downlink skips and forgets what the start version holds (the
// mapping starts from it) and forgets what a newer committed version holds (a restart would start
// from that one): its journal keeps only what no committed version has yet.
#include <cstdint>
#include <map>
#include <optional>
#include <string>

namespace ltm::link {

class SiteWatermarks {
  public:
    // run -> every seq <= through is in the version's map.
    using Through = std::map<std::uint64_t, std::uint64_t>;

    // The start version as the mapping resolves it (`version`: named, or "" for the newest intact
    // one). Throws common::IoError (one line) for a named version unknown or damaged, or a record
    // that cannot be read.
    SiteWatermarks(std::string site_dir, const std::string& version, std::string robot);

    const std::string& start_name() const { return start_name_; }  // "" on a new site
    const Through& start() const { return start_; }
    // "" unless the start version's record was not used (written with another save's manifest).
    const std::string& start_note() const { return start_note_; }

    // A version committed since the newest one seen (checked whole: map and maintained map)
    // and its record; nullopt when there is none. A version that is not whole is passed over
    // (said in *note, once); one whose record is unreadable too.
    struct Newer {
        std::string name;
        Through through;
    };
    std::optional<Newer> poll(std::string* note);

  private:
    std::string site_dir_, robot_, start_name_, start_note_;
    std::uint32_t seen_ = 0;  // the newest version number looked at
    Through start_;
};

}  // namespace ltm::link
