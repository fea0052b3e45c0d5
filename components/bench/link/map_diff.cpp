// ltm_map_diff A B: how far apart two saved maps of the same scans are (the base station's map
// over a link against the composed run's): their local maps' anchors, matched by session and
// local map id, and their active loop edges. `--tolerance M` (and `--require-same-loops`) makes
// the exit code say whether they are the same map.
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "common/cli/cli.hpp"
#include "map/core/map_store.hpp"

namespace {

using Key = std::pair<std::uint32_t, std::uint64_t>;  // session, local map id

struct Loaded {
    std::map<Key, Eigen::Isometry3d, std::less<Key>,
             Eigen::aligned_allocator<std::pair<const Key, Eigen::Isometry3d>>>
        anchors;
    std::set<std::pair<Key, Key>> loops;
    std::size_t keyframes = 0;
};

Loaded load(const std::string& dir) {
    const ltm::map::LoadedMap m = ltm::map::load_map(dir);
    for (const std::string& r : m.refused)
        std::fprintf(stderr, "%s: %s (left out)\n", dir.c_str(), r.c_str());
    Loaded out;
    std::map<std::uint64_t, Key> key_of;
    for (const auto& n : m.map.nodes) {
        const Key k{n.session, n.local_map_id};
        key_of[n.id] = k;
        out.anchors[k] = n.T_world_anchor;
    }
    for (const auto& e : m.map.edges)
        if (e.kind == ltm::map::EdgeKind::kLoop && e.active)
            out.loops.insert({key_of[e.from], key_of[e.to]});
    out.keyframes = m.map.keyframes.size();
    return out;
}

double quantile(std::vector<double> v, double q) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    return v[static_cast<std::size_t>(q * (v.size() - 1) + 0.5)];
}

}  // namespace

int main(int argc, char** argv) {
    std::string a_dir, b_dir;
    double tolerance = -1.0;
    bool same_loops = false;
    CLI::App app{"Two saved maps of the same scans compared: anchors by local map id, loop edges",
                 "ltm_map_diff"};
    ltm::common::cli::configure(app);
    app.add_option("A", a_dir, "a saved map folder (e.g. the composed run's)")->required();
    app.add_option("B", b_dir, "another (e.g. the base station's over the link)")->required();
    app.add_option("--tolerance", tolerance,
                   "exit 1 unless every anchor is in both maps and within this many metres")
        ->check(ltm::common::cli::at_least(0.0));
    app.add_flag("--require-same-loops", same_loops, "exit 1 unless the loop edges are the same");
    if (const int code = ltm::common::cli::parse(app, argc, argv); code >= 0) return code;
    Loaded a, b;
    try {
        a = load(a_dir);
        b = load(b_dir);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "ltm_map_diff: %s\n", e.what());
        return 2;
    }
    std::vector<double> dt, dr;
    std::size_t only_a = 0, only_b = 0;
    for (const auto& [k, T] : a.anchors) {
        const auto it = b.anchors.find(k);
        if (it == b.anchors.end()) {
            ++only_a;
            continue;
        }
        const Eigen::Isometry3d D = T.inverse() * it->second;
        dt.push_back(D.translation().norm());
        dr.push_back(Eigen::AngleAxisd(D.rotation()).angle() * 180.0 / M_PI);
    }
    for (const auto& [k, T] : b.anchors) only_b += a.anchors.count(k) ? 0 : 1;
    std::size_t common_loops = 0;
    for (const auto& l : a.loops) common_loops += b.loops.count(l);
    std::printf("local maps: %zu in A, %zu in B, %zu in both (%zu only in A, %zu only in B)\n",
                a.anchors.size(), b.anchors.size(), dt.size(), only_a, only_b);
    std::printf("keyframes: %zu in A, %zu in B\n", a.keyframes, b.keyframes);
    std::printf(
        "anchor difference: median %.2f mm, max %.2f mm; rotation median %.4f deg, max %.4f deg\n",
        quantile(dt, 0.5) * 1e3, quantile(dt, 1.0) * 1e3, quantile(dr, 0.5), quantile(dr, 1.0));
    std::printf("loops: %zu in A, %zu in B, %zu in both\n", a.loops.size(), b.loops.size(),
                common_loops);
    bool ok = true;
    if (tolerance >= 0 && (only_a > 0 || only_b > 0 || quantile(dt, 1.0) > tolerance)) ok = false;
    if (same_loops && (common_loops != a.loops.size() || common_loops != b.loops.size()))
        ok = false;
    if (tolerance >= 0 || same_loops) std::printf("%s\n", ok ? "same map" : "DIFFERENT maps");
    return ok ? 0 : 1;
}
