#include "simulator/core/scenario_yaml.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "simulator/core/yaml_reader.hpp"

namespace ltm::sim {
namespace {

using Y = YAML::Node;

Eigen::AlignedBox2d box2(const YamlReader& r, const Y& map, const char* name,
                         const std::string& key, const Eigen::AlignedBox2d& fallback) {
    std::vector<double> v;
    if (!r.get_numbers(map, name, key, 4, v)) return fallback;
    if (!(v[2] > v[0] && v[3] > v[1]))
        r.fail(map[name], YamlReader::join(key, name), "expected [xmin, ymin, xmax, ymax]");
    return {Eigen::Vector2d(v[0], v[1]), Eigen::Vector2d(v[2], v[3])};
}

Points2 points2(const YamlReader& r, const Y& node, const std::string& key) {
    r.expect_sequence(node, key);
    Points2 out;
    for (std::size_t i = 0; i < node.size(); ++i) {
        const auto v = r.numbers(node[i], YamlReader::index(key, i), 2, 2);
        out.emplace_back(v[0], v[1]);
    }
    return out;
}

void read_sensor(const YamlReader& r, const Y& n, SensorConfig& s) {
    const std::string k = "sensor";
    r.expect_map(
        n, k,
        {"model", "rate", "height", "min_range", "max_range", "range_at_10pct", "range_noise",
         "dropout", "intensity_noise", "per_point_time", "motion_distortion", "ego_box",
         "elevations_deg", "beam_origin_z", "columns", "points_per_scan", "fov_deg", "lasers"});
    std::string model = "vlp32c";
    r.get(n, "model", k, model);
    if (!make_sensor_preset(model, s))
        r.fail(n["model"], k + ".model", "unknown sensor (known: " + sensor_preset_names() + ")");
    r.get(n, "rate", k, s.rate_hz);
    r.get(n, "height", k, s.height);
    r.get(n, "min_range", k, s.min_range);
    r.get(n, "max_range", k, s.max_range);
    r.get(n, "range_at_10pct", k, s.range_at_10pct);
    r.get(n, "range_noise", k, s.range_noise);
    r.get(n, "dropout", k, s.dropout);
    r.get(n, "intensity_noise", k, s.intensity_noise);
    r.get(n, "per_point_time", k, s.per_point_time);
    r.get(n, "motion_distortion", k, s.motion_distortion);
    r.get_numbers(n, "elevations_deg", k, 0, s.elevations_deg);
    r.get_numbers(n, "beam_origin_z", k, 0, s.beam_origin_z);
    r.get(n, "columns", k, s.columns);
    r.get(n, "points_per_scan", k, s.points_per_scan);
    r.get(n, "fov_deg", k, s.fov_deg);
    r.get(n, "lasers", k, s.rosette_lasers);
    std::vector<double> b;
    if (r.get_numbers(n, "ego_box", k, 6, b)) {
        s.has_ego_box = true;
        s.ego_box = Eigen::AlignedBox3d(Eigen::Vector3d(b[0], b[1], b[2]),
                                        Eigen::Vector3d(b[3], b[4], b[5]));
        if (s.ego_box.isEmpty())
            r.fail(n["ego_box"], k + ".ego_box", "expected [xmin, ymin, zmin, xmax, ymax, zmax]");
    }
}

PlacedObject read_object(const YamlReader& r, const Y& n, const std::string& k) {
    r.expect_map(n, k, {"kind", "x", "y", "yaw", "size", "parked"});
    PlacedObject o;
    std::string kind;
    if (!r.get(n, "kind", k, kind)) r.fail(n, k, "needs a kind");
    if (!parse_object_kind(kind, o.kind))
        r.fail(n["kind"], k + ".kind", "unknown object kind '" + kind + "'");
    if (!r.get(n, "x", k, o.x) || !r.get(n, "y", k, o.y)) r.fail(n, k, "needs x and y");
    r.get(n, "yaw", k, o.yaw_deg);
    std::vector<double> s;
    if (r.get_numbers(n, "size", k, 3, s)) o.size = Eigen::Vector3d(s[0], s[1], s[2]);
    r.get(n, "parked", k, o.parked);
    return o;
}

std::vector<PlacedObject> read_objects(const YamlReader& r, const Y& n, const std::string& k) {
    std::vector<PlacedObject> out;
    if (!n) return out;
    r.expect_sequence(n, k);
    for (std::size_t i = 0; i < n.size(); ++i)
        out.push_back(read_object(r, n[i], YamlReader::index(k, i)));
    return out;
}

void read_world(const YamlReader& r, const Y& n, WorldConfig& w) {
    const std::string k = "world";
    r.expect_map(n, k,
                 {"style", "margin", "road_width", "tree_density", "terrain", "substation", "town",
                  "objects"});
    std::string style = "substation";
    r.get(n, "style", k, style);
    if (style == "substation")
        w.style = WorldStyle::kSubstation;
    else if (style == "town")
        w.style = WorldStyle::kTown;
    else
        r.fail(n["style"], k + ".style", "expected substation or town");
    r.get(n, "margin", k, w.margin);
    r.get(n, "road_width", k, w.road_width);
    r.get(n, "tree_density", k, w.tree_density);
    const Y t = n["terrain"];
    r.expect_map(t, k + ".terrain", {"amplitude", "wavelength", "cell"});
    r.get(t, "amplitude", k + ".terrain", w.terrain.amplitude);
    r.get(t, "wavelength", k + ".terrain", w.terrain.wavelength);
    r.get(t, "cell", k + ".terrain", w.terrain.cell);
    const Y s = n["substation"];
    const std::string ks = k + ".substation";
    r.expect_map(s, ks,
                 {"yard", "bay_width", "equipment_density", "fence_segment", "parking",
                  "parking_occupancy"});
    w.substation.yard = box2(r, s, "yard", ks, w.substation.yard);
    w.substation.parking = box2(r, s, "parking", ks, w.substation.parking);
    r.get(s, "bay_width", ks, w.substation.bay_width);
    r.get(s, "equipment_density", ks, w.substation.equipment_density);
    r.get(s, "fence_segment", ks, w.substation.fence_segment);
    r.get(s, "parking_occupancy", ks, w.substation.parking_occupancy);
    const Y tw = n["town"];
    const std::string kt = k + ".town";
    r.expect_map(tw, kt,
                 {"parked_car_probability", "tree_spacing", "pole_spacing", "building_probability",
                  "second_row_probability"});
    r.get(tw, "parked_car_probability", kt, w.town.parked_car_probability);
    r.get(tw, "tree_spacing", kt, w.town.tree_spacing);
    r.get(tw, "pole_spacing", kt, w.town.pole_spacing);
    r.get(tw, "building_probability", kt, w.town.building_probability);
    r.get(tw, "second_row_probability", kt, w.town.second_row_probability);
    w.objects = read_objects(r, n["objects"], k + ".objects");
}

void read_route(const YamlReader& r, const Y& n, const std::string& k, RouteConfig& route) {
    r.expect_map(n, k,
                 {"speed", "corner_radius", "waypoints", "poses_file", "times_file", "calib_file",
                  "camera_frame", "laps"});
    r.get(n, "speed", k, route.speed);
    r.get(n, "laps", k, route.laps);
    r.get(n, "corner_radius", k, route.corner_radius);
    r.get(n, "poses_file", k, route.poses_file);
    r.get(n, "times_file", k, route.times_file);
    r.get(n, "calib_file", k, route.calib_file);
    r.get(n, "camera_frame", k, route.camera_frame);
    if (const Y w = n["waypoints"]) {
        r.expect_sequence(w, k + ".waypoints");
        for (std::size_t i = 0; i < w.size(); ++i) {
            const std::string ki = YamlReader::index(k + ".waypoints", i);
            if (w[i].IsMap()) {  // {x, y, speed, spin, spin_time}
                r.expect_map(w[i], ki, {"x", "y", "speed", "spin", "spin_time"});
                Waypoint p;
                if (!r.get(w[i], "x", ki, p.x) || !r.get(w[i], "y", ki, p.y))
                    r.fail(w[i], ki, "needs x and y");
                r.get(w[i], "speed", ki, p.speed);
                r.get(w[i], "spin", ki, p.spin_deg);
                r.get(w[i], "spin_time", ki, p.spin_time);
                route.waypoints.push_back(p);
                continue;
            }
            const auto v = r.numbers(w[i], ki, 2, 3);
            route.waypoints.push_back({v[0], v[1], v.size() > 2 ? v[2] : 0.0});
        }
    }
}

void read_actors(const YamlReader& r, const Y& n, const std::string& k, ActorsConfig& a) {
    r.expect_map(n, k, {"vehicles", "pedestrians", "placed"});
    r.get(n, "vehicles", k, a.vehicles);
    r.get(n, "pedestrians", k, a.pedestrians);
    if (!n || !n["placed"]) return;
    const Y p = n["placed"];
    r.expect_sequence(p, k + ".placed");
    for (std::size_t i = 0; i < p.size(); ++i) {
        const std::string ki = YamlReader::index(k + ".placed", i);
        r.expect_map(p[i], ki, {"kind", "speed", "start_offset", "waypoints"});
        ActorConfig c;
        std::string kind = "pedestrian";
        r.get(p[i], "kind", ki, kind);
        if (kind == "car")
            c.kind = ActorKind::kCar;
        else if (kind == "van")
            c.kind = ActorKind::kVan;
        else if (kind == "pedestrian")
            c.kind = ActorKind::kPedestrian;
        else
            r.fail(p[i]["kind"], ki + ".kind", "expected car, van or pedestrian");
        r.get(p[i], "speed", ki, c.speed);
        r.get(p[i], "start_offset", ki, c.start_offset);
        if (!p[i]["waypoints"]) r.fail(p[i], ki, "needs waypoints");
        c.waypoints = points2(r, p[i]["waypoints"], ki + ".waypoints");
        a.placed.push_back(c);
    }
}

void read_changes(const YamlReader& r, const Y& n, const std::string& k, ChangesConfig& c) {
    r.expect_map(n, k,
                 {"move_parked", "remove_parked", "add_parked", "add_containers",
                  "remove_fence_segments", "add", "remove_at"});
    r.get(n, "move_parked", k, c.move_parked);
    r.get(n, "remove_parked", k, c.remove_parked);
    r.get(n, "add_parked", k, c.add_parked);
    r.get(n, "add_containers", k, c.add_containers);
    r.get(n, "remove_fence_segments", k, c.remove_fence_segments);
    if (!n) return;
    c.add = read_objects(r, n["add"], k + ".add");
    if (n["remove_at"]) c.remove_at = points2(r, n["remove_at"], k + ".remove_at");
}

// The node of a key as validate_scenario() names it ("sessions[0].route.speed"), or of the deepest
// part of it the file has (a default value has no line of its own).
Y node_of(const Y& root, const std::string& key) {
    Y node;
    node.reset(root);  // reset, not assignment: assigning a node would change the document
    for (std::size_t i = 0; i < key.size();) {
        Y next;
        if (key[i] == '[') {
            const std::size_t close = key.find(']', i);
            const std::size_t index = std::stoul(key.substr(i + 1, close - i - 1));
            if (!node.IsSequence() || index >= node.size()) break;
            next.reset(static_cast<const Y&>(node)[index]);
            i = close + 1;
        } else {
            if (key[i] == '.') ++i;
            const std::size_t end = std::min(key.find_first_of(".[", i), key.size());
            const std::string name = key.substr(i, end - i);
            if (!node.IsMap() || !static_cast<const Y&>(node)[name]) break;
            next.reset(static_cast<const Y&>(node)[name]);
            i = end;
        }
        node.reset(next);
    }
    return node;
}

SessionConfig read_session(const YamlReader& r, const Y& n, const std::string& k) {
    r.expect_map(
        n, k, {"name", "start_time", "route", "kidnaps", "kidnapped_start", "actors", "changes"});
    SessionConfig s;
    r.get(n, "name", k, s.name);
    r.get(n, "start_time", k, s.start_time);
    r.get(n, "kidnapped_start", k, s.kidnapped_start);
    if (!n["route"]) r.fail(n, k + ".route", "missing (waypoints or a poses_file)");
    read_route(r, n["route"], k + ".route", s.route);
    if (const Y kn = n["kidnaps"]) {
        r.expect_sequence(kn, k + ".kidnaps");
        for (std::size_t i = 0; i < kn.size(); ++i) {
            const std::string ki = YamlReader::index(k + ".kidnaps", i);
            r.expect_map(kn[i], ki, {"at", "resume_at", "resume_at_waypoint", "pause"});
            KidnapConfig kc;
            if (!r.get(kn[i], "at", ki, kc.at)) r.fail(kn[i], ki, "needs at (route time [s])");
            r.get(kn[i], "resume_at", ki, kc.resume_at);
            r.get(kn[i], "resume_at_waypoint", ki, kc.resume_at_waypoint);
            r.get(kn[i], "pause", ki, kc.pause);
            s.kidnaps.push_back(kc);
        }
    }
    read_actors(r, n["actors"], k + ".actors", s.actors);
    read_changes(r, n["changes"], k + ".changes", s.changes);
    return s;
}

}  // namespace

ScenarioConfig parse_scenario(const std::string& text, const std::string& source,
                              const std::string& base_dir) {
    YamlReader r(source);
    Y root;
    try {
        root = YAML::Load(text);
    } catch (const YAML::ParserException& e) {
        throw ScenarioError(source + ":" + std::to_string(e.mark.line + 1) +
                            ": not valid YAML: " + e.msg);
    }
    if (!root.IsMap())
        throw ScenarioError(source + ": expected a map with sensor, world and sessions");
    r.expect_map(root, "", {"name", "seed", "sensor", "world", "sessions"});
    ScenarioConfig sc;
    sc.base_dir = base_dir;
    r.get(root, "name", "", sc.name);
    r.get(root, "seed", "", sc.seed);
    make_sensor_preset("vlp32c", sc.sensor);
    if (root["sensor"]) read_sensor(r, root["sensor"], sc.sensor);
    if (root["world"]) read_world(r, root["world"], sc.world);
    const Y sessions = root["sessions"];
    if (!sessions) r.fail(root, "sessions", "missing (at least one session with a route)");
    r.expect_sequence(sessions, "sessions");
    for (std::size_t i = 0; i < sessions.size(); ++i) {
        sc.sessions.push_back(read_session(r, sessions[i], YamlReader::index("sessions", i)));
    }
    if (const auto problem = validate_scenario(sc)) {
        r.fail(node_of(root, problem->key), problem->key, problem->problem);
    }
    return sc;
}

ScenarioConfig load_scenario(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw ScenarioError(path + ": cannot open the scenario file");
    std::stringstream text;
    text << in.rdbuf();
    const std::size_t slash = path.find_last_of('/');
    const std::string dir = slash == std::string::npos ? "." : path.substr(0, slash);
    return parse_scenario(text.str(), path, dir);
}

}  // namespace ltm::sim
