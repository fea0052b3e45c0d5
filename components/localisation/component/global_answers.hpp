#pragma once
// The localisation component's global queries (global_thread): the global localiser they run on
// (the map version's in use, swapped in by the worker with its localiser) and the newest answer,
// left by the global thread for the worker's next scan. A query keeps scratch state in its global
// localiser: it is never shared with tracking. Thread-safe.
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "localisation/core/global_localiser.hpp"
#include "localisation/core/global_query.hpp"
#include "localisation/core/localiser.hpp"

namespace ltm::localisation {

class GlobalAnswers {
  public:
    // The worker: the global localiser of the version it localises on (a query under way on the
    // old one finishes there: its answer holds in the same map frame).
    void use(std::shared_ptr<GlobalLocaliser> global);

    // The global thread: answers `request` and keeps the answer; the log line with its
    // wall-clock span (`./ltm bench budget` sets the poses published meanwhile against it).
    // `t0`: when the query was taken (wall_clock_s). Throws std::logic_error without a global
    // localiser (a localiser asks only with one).
    std::string answer(const GlobalRequest& request, double t0);

    // The worker, before a scan: the answer waiting, given to `localiser`.
    void give(Localiser& localiser);

    static double wall_clock_s();  // the system clock [s]

  private:
    std::mutex global_mutex_;
    std::shared_ptr<GlobalLocaliser> global_;
    std::mutex answer_mutex_;
    std::optional<GlobalAnswer> answer_;
};

}  // namespace ltm::localisation
