#include "localisation/component/version_loader.hpp"

#include <utility>

#include "common/core/one_line.hpp"
#include "localisation/component/loaded_localiser.hpp"

namespace ltm::localisation {

VersionLoader::VersionLoader(std::string site_dir, std::uint32_t in_use, double poll_s,
                             LocalisationMapConfig map_config, LocaliserConfig config,
                             std::function<void(bool, const std::string&)> say, bool with_global)
    : follower_(std::move(site_dir), in_use),
      poll_s_(poll_s),
      map_config_(std::move(map_config)),
      config_(std::move(config)),
      say_(std::move(say)),
      with_global_(with_global) {}

VersionLoader::~VersionLoader() {
    if (next_.valid()) next_.wait();
}

std::optional<VersionLoader::Loaded> VersionLoader::poll() {
    if (next_.valid()) {
        if (next_.wait_for(std::chrono::seconds(0)) != std::future_status::ready)
            return std::nullopt;
        Result r = next_.get();
        if (r.settings != settings_) return std::nullopt;  // retuned meanwhile: looked at again
        for (const std::string& note : r.notes)
            say_(true, "site " + follower_.site_dir() + ": " + note);
        if (!r.version) return std::nullopt;
        follower_.adopt(r.version->number);  // a version that does not load is not tried again
        if (!r.error.empty()) {
            say_(false, "site " + follower_.site_dir() + ": " + r.version->name +
                            " does not load: " + r.error + " (staying on what runs)");
            return std::nullopt;
        }
        return Loaded{std::move(*r.version), std::move(r.localiser), std::move(r.global), r.load_s};
    }
    const auto now = std::chrono::steady_clock::now();
    if (now - last_look_ < std::chrono::duration<double>(poll_s_)) return std::nullopt;
    last_look_ = now;
    next_ = std::async(std::launch::async, [this] { return look(); });
    return std::nullopt;
}

void VersionLoader::retune(LocalisationMapConfig map_config, LocaliserConfig config) {
    if (next_.valid()) next_.wait();  // look() reads the settings
    map_config_ = std::move(map_config);
    config_ = std::move(config);
    ++settings_;
}

VersionLoader::Result VersionLoader::look() {
    Result r;
    r.settings = settings_;
    r.version = follower_.newer(&r.notes);
    if (!r.version) return r;
    try {
        LoadedLocaliser l =
            load_localiser(r.version->map_dir(), map_config_, config_, with_global_);
        for (const std::string& s : l.refused) r.notes.push_back("map: " + s + " (left out)");
        r.localiser = std::move(l.localiser);
        r.global = std::move(l.global);
        r.load_s = l.load_s;
    } catch (const std::exception& e) {
        r.error = common::one_line(e.what());
    }
    return r;
}

}  // namespace ltm::localisation
