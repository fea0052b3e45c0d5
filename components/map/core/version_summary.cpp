#include "map/core/version_summary.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <map>
#include <sstream>
#include <unordered_map>
#include <utility>
#include <vector>

#include "common/core/file_io.hpp"
#include "common/core/io_error.hpp"
#include "map/core/map_codec.hpp"
#include "map/core/map_manifest.hpp"

namespace ltm::map {
namespace {

namespace fs = std::filesystem;

constexpr double kRadToDeg = 180.0 / M_PI;
constexpr double kSameStamp = 1e-6;  // [s]

using KeyframeKey = std::pair<std::uint32_t, std::uint64_t>;  // session, keyframe id

struct Pose {
    double stamp = 0.0;
    Eigen::Vector3d t = Eigen::Vector3d::Zero();
    Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
};

// What the summary needs of a map: its manifest, and every keyframe's map-frame pose.
struct Skeleton {
    Manifest manifest;
    std::map<KeyframeKey, Pose> keyframes;
    std::uint32_t last_session = 0;
};

Skeleton read_skeleton(const std::string& dir) {
    Skeleton s;
    const fs::path root(dir);
    s.manifest = parse_manifest(common::read_file((root / kManifestFile).string(), kManifestFile));
    std::unordered_map<std::uint64_t, Eigen::Isometry3d> anchors;
    for (const ManifestEntry& e : s.manifest.files) {
        if (e.kind != "graph") continue;
        std::uint64_t revision = 0;
        std::vector<PoseGraphNode> nodes;
        std::vector<PoseGraphEdge> edges;
        decode_graph(common::read_file((root / e.file).string(), e.file), e.file, &revision, &nodes,
                     &edges);
        for (const PoseGraphNode& n : nodes) {
            anchors[n.id] = n.T_world_anchor;
            s.last_session = std::max(s.last_session, n.session);
        }
    }
    for (const SessionRecord& r : s.manifest.sessions)
        s.last_session = std::max(s.last_session, r.id);
    for (const ManifestEntry& e : s.manifest.files) {
        if (e.kind != "keyframes") continue;
        std::uint64_t first = 0;
        const auto keyframes = decode_keyframes(common::read_file((root / e.file).string(), e.file),
                                                e.file, nullptr, &first);
        for (const auto& k : keyframes) {
            const auto anchor = anchors.find(k->node);
            if (anchor == anchors.end()) continue;  // load_map refuses these: not counted
            const Eigen::Isometry3d T = anchor->second * k->data.T_anchor_lidar;
            s.keyframes[{k->session, k->data.id}] =
                Pose{k->data.stamp, T.translation(), Eigen::Quaterniond(T.rotation())};
        }
    }
    return s;
}

std::map<std::uint64_t, std::uint64_t> local_map_hashes(const Manifest& m) {
    std::map<std::uint64_t, std::uint64_t> out;
    for (const ManifestEntry& e : m.files)
        if (e.kind == "local_map") out[e.node] = e.hash;
    return out;
}

template <class T>
bool parse_number(const std::string& text, T* v) {
    if constexpr (std::is_floating_point<T>::value) {
        char* end = nullptr;
        const double d = std::strtod(text.c_str(), &end);
        if (text.empty() || *end != '\0' || !std::isfinite(d)) return false;
        *v = T(d);
        return true;
    } else {
        const auto r = std::from_chars(text.data(), text.data() + text.size(), *v);
        return r.ec == std::errc() && r.ptr == text.data() + text.size();
    }
}

// "3:robot1 4:-" -> {3, robot1}, {4, ""}.
bool parse_sessions(const std::string& value,
                    std::vector<std::pair<std::uint32_t, std::string>>* out) {
    std::istringstream in(value);
    for (std::string item; in >> item;) {
        const auto colon = item.find(':');
        std::uint32_t id = 0;
        if (colon == std::string::npos || colon + 1 == item.size() ||
            !parse_number(item.substr(0, colon), &id))
            return false;
        const std::string robot = item.substr(colon + 1);
        out->emplace_back(id, robot == "-" ? "" : robot);
    }
    return !out->empty();
}

std::string fixed(double v, int digits) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", digits, v);
    return buf;
}

}  // namespace

VersionSummary measure_version(const std::string& new_map_dir, const std::string& start_map_dir,
                               const std::string& start_name) {
    VersionSummary s;
    s.started_from = start_name;
    const Skeleton now = read_skeleton(new_map_dir);
    Skeleton before;
    if (!start_map_dir.empty()) before = read_skeleton(start_map_dir);
    s.session = now.last_session;
    for (const SessionRecord& r : now.manifest.sessions) {
        bool known = false;
        for (const SessionRecord& b : before.manifest.sessions) known |= b.id == r.id;
        if (!known) s.sessions_added.emplace_back(r.id, r.robot);
    }

    const auto maps_now = local_map_hashes(now.manifest);
    const auto maps_before = local_map_hashes(before.manifest);
    s.local_maps = maps_now.size();
    for (const auto& [node, hash] : maps_now) {
        const auto b = maps_before.find(node);
        if (b == maps_before.end())
            ++s.local_maps_added;
        else if (b->second != hash)
            ++s.local_maps_updated;
    }
    for (const auto& entry : maps_before)
        if (!maps_now.count(entry.first)) ++s.local_maps_removed;

    s.keyframes = now.keyframes.size();
    double shift_sum = 0.0, turn_sum = 0.0;
    const Pose* previous = nullptr;  // the previous added keyframe (of the same session)
    std::uint32_t previous_session = 0;
    for (const auto& [key, pose] : now.keyframes) {
        const auto b = before.keyframes.find(key);
        if (b != before.keyframes.end() && std::abs(b->second.stamp - pose.stamp) < kSameStamp) {
            const double shift = (pose.t - b->second.t).norm();
            const double turn = pose.q.angularDistance(b->second.q) * kRadToDeg;
            ++s.keyframes_compared;
            shift_sum += shift;
            turn_sum += turn;
            s.shift_max_m = std::max(s.shift_max_m, shift);
            s.turn_max_deg = std::max(s.turn_max_deg, turn);
            continue;
        }
        ++s.keyframes_added;
        if (previous && previous_session == key.first)
            s.trajectory_m += (pose.t - previous->t).norm();
        previous = &pose;
        previous_session = key.first;
    }
    if (s.keyframes_compared > 0) {
        s.shift_mean_m = shift_sum / double(s.keyframes_compared);
        s.turn_mean_deg = turn_sum / double(s.keyframes_compared);
    }
    return s;
}

std::string write_version_text(const VersionSummary& s) {
    std::ostringstream o;
    o << "ltm_site_version 1\n"
      << "number " << s.number << "\n"
      << "created " << s.created << "\n"
      << "started_from " << (s.started_from.empty() ? "-" : s.started_from) << "\n"
      << "session " << s.session << "\n";
    if (!s.sessions_added.empty()) {
        o << "sessions_added";
        for (const auto& [id, robot] : s.sessions_added)
            o << " " << id << ":" << (robot.empty() ? "-" : robot);
        o << "\n";
    }
    o << "local_maps " << s.local_maps << "\n"
      << "local_maps_added " << s.local_maps_added << "\n"
      << "local_maps_updated " << s.local_maps_updated << "\n"
      << "local_maps_removed " << s.local_maps_removed << "\n"
      << "keyframes " << s.keyframes << "\n"
      << "keyframes_added " << s.keyframes_added << "\n"
      << "trajectory_m " << fixed(s.trajectory_m, 2) << "\n";
    if (s.voxels_removed) o << "voxels_removed " << *s.voxels_removed << "\n";
    if (s.voxels_added) o << "voxels_added " << *s.voxels_added << "\n";
    o << "keyframes_compared " << s.keyframes_compared << "\n"
      << "shift_max_m " << fixed(s.shift_max_m, 6) << "\n"
      << "shift_mean_m " << fixed(s.shift_mean_m, 6) << "\n"
      << "turn_max_deg " << fixed(s.turn_max_deg, 6) << "\n"
      << "turn_mean_deg " << fixed(s.turn_mean_deg, 6) << "\n";
    return o.str();
}

VersionSummary parse_version_text(const std::string& text, const std::string& name) {
    VersionSummary s;
    std::istringstream in(text);
    std::string line;
    int number = 0;
    std::uint64_t offset = 0;
    bool header = false;
    while (std::getline(in, line)) {
        ++number;
        const std::uint64_t at = offset;
        offset += line.size() + 1;
        if (line.empty()) continue;
        const auto space = line.find(' ');
        const std::string key = line.substr(0, space);
        const std::string value = space == std::string::npos ? "" : line.substr(space + 1);
        const std::string where = "line " + std::to_string(number);
        auto fail = [&](const std::string& problem) -> void {
            throw common::FormatError(name, where, at, problem);
        };
        if (number == 1) {
            if (key != "ltm_site_version" || value != "1")
                fail("not a site version summary (expected 'ltm_site_version 1')");
            header = true;
            continue;
        }
        bool ok = true;
        std::uint64_t u = 0;
        if (key == "number")
            ok = parse_number(value, &s.number);
        else if (key == "created")
            ok = parse_number(value, &s.created);
        else if (key == "started_from")
            s.started_from = value == "-" ? "" : value;
        else if (key == "session")
            ok = parse_number(value, &s.session);
        else if (key == "sessions_added")
            ok = parse_sessions(value, &s.sessions_added);
        else if (key == "local_maps")
            ok = parse_number(value, &s.local_maps);
        else if (key == "local_maps_added")
            ok = parse_number(value, &s.local_maps_added);
        else if (key == "local_maps_updated")
            ok = parse_number(value, &s.local_maps_updated);
        else if (key == "local_maps_removed")
            ok = parse_number(value, &s.local_maps_removed);
        else if (key == "keyframes")
            ok = parse_number(value, &s.keyframes);
        else if (key == "keyframes_added")
            ok = parse_number(value, &s.keyframes_added);
        else if (key == "trajectory_m")
            ok = parse_number(value, &s.trajectory_m);
        else if (key == "voxels_removed") {
            ok = parse_number(value, &u);
            s.voxels_removed = u;
        } else if (key == "voxels_added") {
            ok = parse_number(value, &u);
            s.voxels_added = u;
        } else if (key == "keyframes_compared")
            ok = parse_number(value, &s.keyframes_compared);
        else if (key == "shift_max_m")
            ok = parse_number(value, &s.shift_max_m);
        else if (key == "shift_mean_m")
            ok = parse_number(value, &s.shift_mean_m);
        else if (key == "turn_max_deg")
            ok = parse_number(value, &s.turn_max_deg);
        else if (key == "turn_mean_deg")
            ok = parse_number(value, &s.turn_mean_deg);
        if (!ok) fail(key + ": '" + value + "' is not a valid value");
    }
    if (!header) throw common::FormatError(name, "empty (expected 'ltm_site_version 1')");
    return s;
}

std::string version_date(std::int64_t created) {
    const std::time_t t = static_cast<std::time_t>(created);
    std::tm tm{};
    gmtime_r(&t, &tm);
    char buf[40];
    std::strftime(buf, sizeof buf, "%Y-%m-%d %H:%M UTC", &tm);
    return buf;
}

std::string version_line(const VersionSummary& s) {
    std::string out = std::to_string(s.local_maps_added) + " local maps added, " +
                      std::to_string(s.local_maps_updated) + " updated";
    if (s.local_maps_removed > 0) out += ", " + std::to_string(s.local_maps_removed) + " removed";
    out += " (" + std::to_string(s.local_maps) + "); " + std::to_string(s.keyframes_added) +
           " keyframes added (" + fixed(s.trajectory_m, 0) + " m)";
    if (s.keyframes_compared > 0)
        out += "; old keyframes moved max " + fixed(s.shift_max_m, 3) + " m / " +
               fixed(s.turn_max_deg, 2) + " deg (mean " + fixed(s.shift_mean_m, 3) + " m)";
    if (s.voxels_removed || s.voxels_added)
        out += "; maintenance: " +
               (s.voxels_removed ? std::to_string(*s.voxels_removed) : std::string("?")) +
               " voxels removed, " +
               (s.voxels_added ? std::to_string(*s.voxels_added) : std::string("?")) + " added";
    bool robots = false;
    for (const auto& [id, robot] : s.sessions_added) robots |= !robot.empty();
    if (robots) {
        out += "; sessions ";
        for (std::size_t i = 0; i < s.sessions_added.size(); ++i)
            out += (i ? ", " : "") + std::to_string(s.sessions_added[i].first) + " (" +
                   (s.sessions_added[i].second.empty() ? "-" : s.sessions_added[i].second) + ")";
    }
    out += s.started_from.empty() ? "; first version" : "; from " + s.started_from;
    return out;
}

}  // namespace ltm::map
