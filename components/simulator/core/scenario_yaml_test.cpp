#include "simulator/core/scenario_yaml.hpp"

#include <gtest/gtest.h>

#include <string>

namespace ltm::sim {
namespace {

const std::string kScenarios = LTM_SOURCE_DIR "/components/simulator/scenarios/";

const char* kMinimal = R"(name: t
seed: 3
sensor: {model: vlp16, rate: 5}
sessions:
  - route:
      waypoints: [[0, 0], [10, 0, 2.5], [10, 10]]
)";

std::string error_of(const std::string& text) {
    try {
        parse_scenario(text, "test.yaml", ".");
    } catch (const ScenarioError& e) {
        return e.what();
    }
    return "";
}

TEST(ScenarioYaml, ShippedScenariosLoad) {
    for (const char* name :
         {"tiny_loop", "site_loop", "site_sessions", "kitti00_path", "fast_turns", "turn_on_spot",
          "repeat_week", "repeat_fortnight", "long_day", "tiny_lost", "handheld_spins"}) {
        const ScenarioConfig sc = load_scenario(kScenarios + name + ".yaml");
        EXPECT_EQ(sc.name, name);
        EXPECT_FALSE(sc.sessions.empty());
        EXPECT_FALSE(validate_scenario(sc)) << validate_scenario(sc)->key;
    }
    const ScenarioConfig sessions = load_scenario(kScenarios + "site_sessions.yaml");
    ASSERT_EQ(sessions.sessions.size(), 2u);
    EXPECT_TRUE(sessions.sessions[1].kidnapped_start);
    EXPECT_EQ(sessions.sessions[1].kidnaps.size(), 1u);
    const ChangesConfig& c = sessions.sessions[1].changes;
    EXPECT_GE(
        c.move_parked + c.remove_parked + c.add_parked + c.add_containers + c.remove_fence_segments,
        10);
    const ScenarioConfig kitti = load_scenario(kScenarios + "kitti00_path.yaml");
    EXPECT_EQ(kitti.sensor.model, "hdl64e");
    EXPECT_EQ(kitti.world.style, WorldStyle::kTown);
    EXPECT_TRUE(kitti.sensor.has_ego_box);
}

TEST(ScenarioYaml, ReadsValuesOverPresets) {
    const ScenarioConfig sc = parse_scenario(kMinimal, "test.yaml", "/base");
    EXPECT_EQ(sc.seed, 3u);
    EXPECT_EQ(sc.sensor.model, "vlp16");
    EXPECT_DOUBLE_EQ(sc.sensor.rate_hz, 5.0);
    EXPECT_EQ(sc.sensor.elevations_deg.size(), 16u);
    ASSERT_EQ(sc.sessions[0].route.waypoints.size(), 3u);
    EXPECT_DOUBLE_EQ(sc.sessions[0].route.waypoints[1].speed, 2.5);
    EXPECT_EQ(sc.base_dir, "/base");
}

TEST(ScenarioYaml, RejectsUnknownKeysNamingKeyAndLine) {
    std::string text = kMinimal;
    text.replace(text.find("rate: 5"), 7, "rate: 5, sped: 3");
    const std::string e = error_of(text);
    EXPECT_NE(e.find("test.yaml:3"), std::string::npos) << e;
    EXPECT_NE(e.find("sensor.sped"), std::string::npos) << e;
    EXPECT_NE(e.find("unknown key"), std::string::npos) << e;
    const std::string nested =
        error_of(std::string(kMinimal) + "    actors: {vehicles: 1, bicycles: 2}\n");
    EXPECT_NE(nested.find("sessions[0].actors.bicycles"), std::string::npos) << nested;
    EXPECT_NE(nested.find("test.yaml:7"), std::string::npos) << nested;
    EXPECT_NE(error_of(std::string(kMinimal) + "colour: red\n").find("colour"), std::string::npos);
}

TEST(ScenarioYaml, RejectsBadValuesWithOneLine) {
    auto check = [](const std::string& text, const std::string& needle) {
        const std::string e = error_of(text);
        EXPECT_NE(e.find(needle), std::string::npos) << e;
        EXPECT_EQ(e.find('\n'), std::string::npos) << e;
    };
    std::string t = kMinimal;
    check(t.replace(t.find("vlp16"), 5, "lidar9"), "unknown sensor");
    t = kMinimal;
    check(t.replace(t.find("rate: 5"), 7, "rate: fast"), "sensor.rate: expected a number");
    t = kMinimal;
    check(t.replace(t.find("rate: 5"), 7, "rate: -1"), "sensor.rate: must be > 0");
    check("sessions: []\n", "at least one session");
    check("name: x\n", "sessions: missing");
    check("sessions:\n  - name: a\n", "sessions[0].route: missing");
    check(std::string(kMinimal) + "    kidnaps: [{at: 3}]\n", "needs resume_at");
    check("sessions: [ {route: {waypoints: [[0, 0], [1]]}} ]\n", "sessions[0].route.waypoints[1]");
    check("{{{", "not valid YAML");
}

TEST(ScenarioYaml, RouteLaps) {
    std::string t = kMinimal;
    const ScenarioConfig one = parse_scenario(t, "test.yaml", ".");
    EXPECT_EQ(one.sessions[0].route.laps, 1);
    const std::string three = t.replace(t.find("waypoints"), 9, "laps: 3\n      waypoints");
    EXPECT_EQ(parse_scenario(three, "test.yaml", ".").sessions[0].route.laps, 3);
    t = three;
    EXPECT_NE(error_of(t.replace(t.find("laps: 3"), 7, "laps: 0")).find("route.laps: must be >= 1"),
              std::string::npos);
    t = three;
    EXPECT_NE(error_of(t.replace(t.find("laps: 3"), 7, "lap: 3")).find("route.lap: unknown key"),
              std::string::npos);
    const std::string file =
        "sessions: [ {route: {laps: 2, poses_file: p.txt, times_file: t.txt}} ]\n";
    EXPECT_NE(error_of(file).find("route.laps: only waypoint routes"), std::string::npos);
}

TEST(ScenarioYaml, TurnsOnTheSpot) {
    const std::string head =
        "sensor: {model: vlp16}\nsessions:\n  - route:\n      waypoints:\n"
        "        - [0, 0]\n";
    const ScenarioConfig sc = parse_scenario(head +
                                                 "        - {x: 10, y: 0, spin: -270, "
                                                 "spin_time: 3, speed: 1.2}\n"
                                                 "        - [10, 10]\n",
                                             "test.yaml", ".");
    const Waypoint& w = sc.sessions[0].route.waypoints[1];
    EXPECT_DOUBLE_EQ(w.x, 10.0);
    EXPECT_DOUBLE_EQ(w.spin_deg, -270.0);
    EXPECT_DOUBLE_EQ(w.spin_time, 3.0);
    EXPECT_DOUBLE_EQ(w.speed, 1.2);
    // The turn must end on the next leg's heading (here +90 deg plus whole turns).
    EXPECT_EQ(error_of(head + "        - {x: 10, y: 0, spin: 180, spin_time: 2}\n"
                              "        - [10, 10]\n"),
              "test.yaml:6: sessions[0].route.waypoints[1].spin: must end on the next leg's "
              "heading: the route turns 90.0 deg here (give that plus whole turns, e.g. -270.0 "
              "or 450.0)");
    EXPECT_NE(error_of(head + "        - {x: 10, y: 0, spin: 90}\n        - [10, 10]\n")
                  .find("waypoints[1].spin: needs a spin_time > 0"),
              std::string::npos);
    EXPECT_NE(error_of(head + "        - {x: 10, y: 0, spin_time: -1}\n        - [10, 10]\n")
                  .find("waypoints[1].spin_time: must be >= 0"),
              std::string::npos);
    EXPECT_NE(error_of(head + "        - {x: 10, spin: 90}\n").find("needs x and y"),
              std::string::npos);
    EXPECT_NE(error_of(head + "        - {x: 10, y: 0, turn: 90}\n").find("unknown key"),
              std::string::npos);
    // Whole turns at the ends are fine once; with laps the ends are joined by a leg.
    const std::string end_spin = head + "        - {x: 10, y: 0, spin: 360, spin_time: 4}\n";
    EXPECT_EQ(error_of(end_spin), "");
    EXPECT_NE(error_of(end_spin + "      laps: 2\n").find("needs laps: 1"), std::string::npos);
}

TEST(ScenarioYaml, RulesBrokenNameTheLineOfTheKey) {
    std::string t = kMinimal;
    EXPECT_EQ(error_of(t.replace(t.find("rate: 5"), 7, "rate: -1")),
              "test.yaml:3: sensor.rate: must be > 0 (got -1)");
    t = kMinimal;
    t.replace(t.find("sessions:"), 9, "world: {town: {tree_spacing: 1}}\nsessions:");
    EXPECT_EQ(error_of(t), "test.yaml:4: world.town.tree_spacing: must be > 1 (got 1)");
    t = kMinimal;  // across fields
    EXPECT_EQ(error_of(t.replace(t.find("rate: 5"), 7, "max_range: 0.5")),
              "test.yaml:3: sensor.max_range: must exceed min_range");
    EXPECT_EQ(error_of(std::string(kMinimal) + "    kidnaps: [{at: 3, pause: -1, resume_at: 5}]\n"),
              "test.yaml:7: sessions[0].kidnaps[0].pause: must be >= 0 (got -1)");
    EXPECT_EQ(error_of(std::string(kMinimal) + "    changes: {add_parked: -2}\n"),
              "test.yaml:7: sessions[0].changes.add_parked: must be >= 0 (got -2)");
    t = kMinimal;
    EXPECT_EQ(error_of(t.replace(t.find("2.5"), 3, "-1")),
              "test.yaml:6: sessions[0].route.waypoints[1]: speed must be >= 0");
    ScenarioConfig none;  // built in code: the key alone
    ASSERT_TRUE(validate_scenario(none));
    EXPECT_EQ(validate_scenario(none)->key, "sessions");
}

TEST(ScenarioYaml, MissingFilesGiveOneLine) {
    try {
        load_scenario("/nonexistent/dir/s.yaml");
        FAIL();
    } catch (const ScenarioError& e) {
        EXPECT_NE(std::string(e.what()).find("/nonexistent/dir/s.yaml"), std::string::npos);
    }
}

}  // namespace
}  // namespace ltm::sim
