#pragma once
// What differs between sessions: parked vehicles moved, gone or new, new containers, fence
// segments taken down, placed additions and removals. Every later session is relative to the
// first one; deterministic by seed.
#include <cstdint>
#include <string>
#include <vector>

#include "simulator/core/layout.hpp"
#include "simulator/core/scenario.hpp"

namespace ltm::sim {

struct ObjectChange {
    int session = 0;  // the session where the change is seen
    std::uint32_t id = 0;
    ObjectKind kind = ObjectKind::kCar;
    std::string what;  // "removed", "moved", "added"
};

struct SessionPlan {
    std::vector<std::vector<ObjectInstance>> objects;  // static objects of each session
    std::vector<std::uint32_t> changed_ids;            // sorted: objects that differ somewhere
    std::vector<ObjectChange> changes;
    std::vector<std::string> warnings;  // changes asked for that found no candidates
    bool is_changed(std::uint32_t id) const;
};

// `routes` are the sessions' route centre lines. Changes are picked among objects within
// `visible_range` of both the first session's route and the changed session's route.
SessionPlan plan_sessions(const Layout& layout, const std::vector<SessionConfig>& sessions,
                          const std::vector<Points2>& routes, std::uint64_t seed,
                          double visible_range = 30.0);

}  // namespace ltm::sim
