#include "localisation/component/global_answers.hpp"

#include <chrono>
#include <cstdio>
#include <stdexcept>

namespace ltm::localisation {
double GlobalAnswers::wall_clock_s() {
    return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch())
        .count();
}

void GlobalAnswers::use(std::shared_ptr<GlobalLocaliser> global) {
    std::lock_guard<std::mutex> lock(global_mutex_);
    global_ = std::move(global);
}

std::string GlobalAnswers::answer(const GlobalRequest& request, double t0) {
    std::shared_ptr<GlobalLocaliser> global;
    {
        std::lock_guard<std::mutex> lock(global_mutex_);
        global = global_;
    }
    // A localiser asks only with its version's global localiser swapped in with it.
    if (!global) throw std::logic_error("a global query without a map to answer it on");
    GlobalAnswer a = localisation::answer(*global, request);
    char text[400];
    std::snprintf(text, sizeof text,
                  "global query for the scan at %.3f s: %.3f s (wall %.3f to %.3f): %s",
                  request.stamp, a.result.time_s, t0, wall_clock_s(),
                  a.result.localised ? "localised" : a.result.reason.c_str());
    std::lock_guard<std::mutex> lock(answer_mutex_);
    answer_ = std::move(a);
    return text;
}

void GlobalAnswers::give(Localiser& localiser) {
    std::lock_guard<std::mutex> lock(answer_mutex_);
    if (answer_) localiser.give_answer(std::move(*answer_));
    answer_.reset();
}

}  // namespace ltm::localisation
