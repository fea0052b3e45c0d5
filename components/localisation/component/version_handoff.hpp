#pragma once
// A newer site version, loaded (version_loader.hpp), handed from the localisation component's
// thread to its worker, which swaps it in before its next scan (its localiser taking over the
// running one's track). A newer one offered before the worker took the last replaces it.
// Thread-safe.
#include <mutex>
#include <optional>
#include <utility>

#include "localisation/component/version_loader.hpp"

namespace ltm::localisation {

class VersionHandoff {
  public:
    void offer(VersionLoader::Loaded&& loaded) {
        std::lock_guard<std::mutex> lock(mutex_);
        pending_ = std::move(loaded);
    }

    // The version waiting, once.
    std::optional<VersionLoader::Loaded> take() {
        std::lock_guard<std::mutex> lock(mutex_);
        std::optional<VersionLoader::Loaded> taken;
        taken.swap(pending_);
        return taken;
    }

  private:
    std::mutex mutex_;
    std::optional<VersionLoader::Loaded> pending_;
};

}  // namespace ltm::localisation
