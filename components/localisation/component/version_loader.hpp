#pragma once
// The localisation component's loader of a site's newer versions (site_poll_s, the split robot):
// every poll_s a look at the site (core/site_follower) on a thread of its own; a newer intact
// version is loaded there and its Localiser built, while the component's worker goes on on the
// old map. The component's timer calls poll() often and gets each loaded version once; it hands
// the localiser to its worker, which swaps it in between two scans (Localiser::take_track). A
// version that does not load is said and not tried again; a newer one is.
#include <chrono>
#include <functional>
#include <future>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "localisation/core/global_localiser.hpp"
#include "localisation/core/localiser.hpp"
#include "localisation/core/site_follower.hpp"

namespace ltm::localisation {

class VersionLoader {
  public:
    struct Loaded {
        map::SiteVersion version;
        std::unique_ptr<Localiser> localiser;
        // with_global: the version's own global localiser (for the component's global thread),
        // its localiser set to ask it (Localiser::set_global_elsewhere).
        std::shared_ptr<GlobalLocaliser> global;
        double load_s = 0.0;  // wall time to load the map and build the localiser
    };
    // `in_use`: the version the session runs on (0: none). `say(warning, line)`: notes on damaged
    // versions and maps left out (warnings), a version that does not load (error).
    VersionLoader(std::string site_dir, std::uint32_t in_use, double poll_s,
                  LocalisationMapConfig map_config, LocaliserConfig config,
                  std::function<void(bool warning, const std::string& line)> say,
                  bool with_global = false);
    ~VersionLoader();  // waits for a load under way
    VersionLoader(const VersionLoader&) = delete;
    VersionLoader& operator=(const VersionLoader&) = delete;

    // Starts a look when poll_s has passed and none is under way; a version loaded since the
    // last call, once.
    std::optional<Loaded> poll();

    // New settings for the versions loaded from now on (`preset: auto` once the scans told a
    // sensor whose settings differ). A look under way is waited for and its version, loaded with
    // the old ones, looked at again. The component's thread (as poll).
    void retune(LocalisationMapConfig map_config, LocaliserConfig config);

  private:
    struct Result {
        std::optional<map::SiteVersion> version;
        std::unique_ptr<Localiser> localiser;
        std::shared_ptr<GlobalLocaliser> global;
        std::vector<std::string> notes;
        std::string error;
        double load_s = 0.0;
        int settings = 0;  // settings_ when the look started
    };
    Result look();  // on the loader's thread

    SiteFollower follower_;  // used by one look() at a time
    double poll_s_;
    LocalisationMapConfig map_config_;
    LocaliserConfig config_;
    int settings_ = 0;  // retunes so far
    std::function<void(bool, const std::string&)> say_;
    bool with_global_;
    std::future<Result> next_;
    std::chrono::steady_clock::time_point last_look_;
};

}  // namespace ltm::localisation
