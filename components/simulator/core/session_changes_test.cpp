#include "simulator/core/session_changes.hpp"

#include <gtest/gtest.h>

#include <map>
#include <set>

#include "common/core/point_labels.hpp"
#include "simulator/core/scenario_yaml.hpp"
#include "simulator/core/simulator.hpp"

namespace ltm::sim {
namespace {

const std::string kScenarios = LTM_SOURCE_DIR "/components/simulator/scenarios/";

std::set<std::uint32_t> ids(const std::vector<ObjectInstance>& objects) {
    std::set<std::uint32_t> out;
    for (const auto& o : objects) out.insert(o.id);
    return out;
}

TEST(SessionChanges, TinyLoopChangesWhatItAsks) {
    const ScenarioConfig sc = load_scenario(kScenarios + "tiny_loop.yaml");
    const Simulator sim(sc, 1);
    const SessionPlan& plan = sim.plan();
    EXPECT_TRUE(plan.warnings.empty()) << plan.warnings.front();
    std::map<std::string, int> what;
    for (const auto& c : plan.changes) {
        EXPECT_EQ(c.session, 1);
        ++what[c.what + " " + object_kind_name(c.kind)];
    }
    EXPECT_EQ(what["moved car"] + what["moved van"], 1);
    EXPECT_EQ(what["removed car"] + what["removed van"], 1);
    EXPECT_EQ(what["added car"] + what["added van"], 1);
    EXPECT_EQ(what["added container"], 1);
    EXPECT_EQ(what["removed fence"], 1);
    EXPECT_EQ(plan.changed_ids.size(), 5u);
    // Session objects differ exactly by the removed and added ids; moved ones stand elsewhere.
    const std::set<std::uint32_t> a = ids(plan.objects[0]), b = ids(plan.objects[1]);
    std::map<std::uint32_t, const ObjectInstance*> before;
    for (const auto& o : plan.objects[0]) before[o.id] = &o;
    for (const auto& c : plan.changes) {
        if (c.what == "removed") {
            EXPECT_TRUE(a.count(c.id) && !b.count(c.id));
        } else if (c.what == "added") {
            EXPECT_TRUE(!a.count(c.id) && b.count(c.id));
        } else {
            ASSERT_TRUE(a.count(c.id) && b.count(c.id));
            for (const auto& o : plan.objects[1]) {
                if (o.id == c.id) {
                    EXPECT_GT(std::hypot(o.x - before[c.id]->x, o.y - before[c.id]->y), 2.0);
                }
            }
        }
    }
    EXPECT_EQ(b.size(), a.size());  // 2 removed (car, fence), 2 added (car, container)
}

TEST(SessionChanges, ChangedObjectsAreLabelledInBothSessions) {
    const ScenarioConfig sc = load_scenario(kScenarios + "tiny_loop.yaml");
    for (int session = 0; session < 2; ++session) {
        const Simulator sim(sc, session);
        std::set<std::uint32_t> seen;
        SimScan scan;
        for (std::size_t i = 0; i < sim.num_scans(); i += 2) {
            ASSERT_TRUE(sim.scan(i, scan));
            for (const std::uint32_t l : scan.labels) {
                if (common::label_class(l) != common::kSimChangedObject) continue;
                EXPECT_TRUE(sim.plan().is_changed(common::label_object_id(l)));
                seen.insert(common::label_object_id(l));
            }
        }
        EXPECT_GE(seen.size(), 2u) << "session " << session;
    }
}

TEST(SessionChanges, SiteSessionsHasTenChangesAndFiveActorsEach) {
    const ScenarioConfig sc = load_scenario(kScenarios + "site_sessions.yaml");
    const Simulator s1(sc, 1);
    EXPECT_TRUE(s1.warnings().empty()) << s1.warnings().front();
    EXPECT_GE(s1.plan().changed_ids.size(), 10u);
    EXPECT_GE(s1.actors().size(), 5u);
    EXPECT_TRUE(s1.after_kidnap(0));
    const Simulator s0(sc, 0);
    EXPECT_GE(s0.actors().size(), 5u);
    EXPECT_EQ(s0.plan().changed_ids, s1.plan().changed_ids);  // one plan for all sessions
}

}  // namespace
}  // namespace ltm::sim
