#include "version_growth.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <unordered_map>
#include <unordered_set>

#include "maintenance/core/long_term_map.hpp"
#include "map/core/map_store.hpp"

namespace ltm::bench {
namespace {

using maintenance::LongTermMap;

std::map<std::uint32_t, std::size_t> keyframes_by_session(const map::MapData& m) {
    std::map<std::uint32_t, std::size_t> n;
    for (const auto& k : m.keyframes) ++n[k->session];
    return n;
}

std::map<std::uint64_t, std::pair<std::size_t, std::uint32_t>> local_maps(const map::MapData& m) {
    std::map<std::uint64_t, std::pair<std::size_t, std::uint32_t>> out;  // node -> voxels, revision
    for (const auto& lm : m.local_maps)
        if (lm.data) out[lm.node] = {lm.data->voxels.size(), lm.data->revision};
    return out;
}

std::uint64_t cell_key(const Eigen::Vector3f& c, float edge) {
    const auto q = [&](float x) {
        return std::uint64_t(std::int64_t(std::floor(x / edge)) & 0x1FFFFF);
    };
    return (q(c.x()) << 42) | (q(c.y()) << 21) | q(c.z());
}

}  // namespace

void print_growth(const std::string& before, const std::string& after,
                  const maintenance::MaintenanceConfig& config) {
    const map::MapData a = map::load_map(before + "/map").map;
    const map::MapData b = map::load_map(after + "/map").map;
    std::printf("growth %s -> %s\n", before.c_str(), after.c_str());
    const auto ka = keyframes_by_session(a), kb = keyframes_by_session(b);
    std::printf("  keyframes %zu -> %zu; by session (before/after):", a.keyframes.size(),
                b.keyframes.size());
    for (const auto& [s, n] : kb) std::printf(" %u:%zu/%zu", s, ka.count(s) ? ka.at(s) : 0, n);
    std::printf("\n");
    const auto la = local_maps(a), lb = local_maps(b);
    std::size_t va = 0, vb = 0, vnew = 0, grown = 0, shrunk = 0;
    std::vector<std::pair<long, std::uint64_t>> change;  // voxel change, node
    for (const auto& [node, vr] : la) va += vr.first;
    for (const auto& [node, vr] : lb) {
        vb += vr.first;
        const auto it = la.find(node);
        if (it == la.end()) {
            vnew += vr.first;
            continue;
        }
        const long d = long(vr.first) - long(it->second.first);
        if (d > 0) ++grown;
        if (d < 0) ++shrunk;
        change.push_back({d, node});
    }
    std::printf(
        "  local maps %zu -> %zu (%zu new, %zu voxels), voxels %zu -> %zu (%+.2f %%); "
        "%zu grew, %zu shrank\n",
        la.size(), lb.size(), lb.size() - std::min(lb.size(), la.size()), vnew, va, vb,
        va ? 100.0 * (double(vb) - double(va)) / double(va) : 0.0, grown, shrunk);
    // The voxels of grown maps in cells the map did not have, by the scans that hit them.
    std::size_t fresh_obs[4] = {0, 0, 0, 0};                // 1-2, 3-5, 6-19, 20+
    std::size_t fresh_points[3] = {0, 0, 0};                // < 5, 5-19, 20+
    std::size_t fresh_beside = 0, fresh_planar_beside = 0;  // a voxel of the map in a next cell
    for (const auto& lm_b : b.local_maps) {
        if (!lm_b.data) continue;
        const common::LocalMapData* before_map = nullptr;
        for (const auto& lm_a : a.local_maps)
            if (lm_a.node == lm_b.node && lm_a.data) before_map = lm_a.data.get();
        if (!before_map) continue;
        std::unordered_set<std::uint64_t> cells;
        const auto key = [](const Eigen::Vector3i& i) {
            return (std::uint64_t(i.x() & 0x1FFFFF) << 42) |
                   (std::uint64_t(i.y() & 0x1FFFFF) << 21) | std::uint64_t(i.z() & 0x1FFFFF);
        };
        for (const auto& v : before_map->voxels) cells.insert(key(v.index));
        for (const auto& v : lm_b.data->voxels) {
            if (cells.count(key(v.index))) continue;
            bool beside = false, planar = false;
            for (int d = 0; d < 27; ++d) {
                const Eigen::Vector3i n =
                    v.index + Eigen::Vector3i(d % 3 - 1, d / 3 % 3 - 1, d / 9 - 1);
                if (d == 13 || !cells.count(key(n))) continue;
                beside = true;
            }
            if (beside && v.planarity > 0.5f) planar = true;
            fresh_beside += beside;
            fresh_planar_beside += planar;
            const auto o = v.life.observations;
            fresh_obs[o <= 2 ? 0 : o <= 5 ? 1 : o <= 19 ? 2 : 3]++;
            const auto n = v.point_count;
            fresh_points[n < 5 ? 0 : n < 20 ? 1 : 2]++;
        }
    }
    std::printf(
        "  voxels in cells a map did not have, by scans that hit them 1-2 / 3-5 / 6-19 / "
        "20+: %zu / %zu / %zu / %zu; by points <5 / 5-19 / 20+: %zu / %zu / %zu\n",
        fresh_obs[0], fresh_obs[1], fresh_obs[2], fresh_obs[3], fresh_points[0], fresh_points[1],
        fresh_points[2]);
    std::printf("  of them beside a voxel the map had (26 next cells): %zu (planar > 0.5: %zu)\n",
                fresh_beside, fresh_planar_beside);
    std::sort(change.rbegin(), change.rend());
    std::printf("  most grown (node: voxels before -> after):");
    for (std::size_t i = 0; i < std::min<std::size_t>(change.size(), 6); ++i) {
        const auto& [d, node] = change[i];
        std::printf(" %lu: %zu -> %zu;", (unsigned long)node, la.at(node).first, lb.at(node).first);
    }
    std::printf("\n");

    const std::string ma = before + "/maintenance/long_term_map.bin";
    const std::string mb = after + "/maintenance/long_term_map.bin";
    if (!std::filesystem::exists(ma) || !std::filesystem::exists(mb)) return;
    const LongTermMap A = LongTermMap::load(ma, config);
    const LongTermMap B = LongTermMap::load(mb, config);
    const float e = float(config.voxel_size);
    std::unordered_set<std::uint64_t> in_a;
    for (const Eigen::Vector3f& c : A.voxel_centres()) in_a.insert(cell_key(c, e));
    const std::vector<Eigen::Vector3f> cb = B.voxel_centres();
    std::unordered_map<std::uint64_t, float> column_floor;  // 2 m columns: the lowest voxel
    const auto column = [](const Eigen::Vector3f& c) {
        return (std::uint64_t(std::int64_t(std::floor(c.x() / 2.0f)) & 0xFFFFFFFF) << 32) |
               std::uint64_t(std::int64_t(std::floor(c.y() / 2.0f)) & 0xFFFFFFFF);
    };
    for (const Eigen::Vector3f& c : cb) {
        auto [it, fresh] = column_floor.emplace(column(c), c.z());
        if (!fresh) it->second = std::min(it->second, c.z());
    }
    std::size_t added = 0, kept = 0, created_now = 0, ground = 0;
    std::size_t by_hits[4] = {0, 0, 0, 0};  // 0-1, 2-4, 5-19, 20+
    std::size_t by_height[3] = {0, 0, 0};   // < 0.5 m, 0.5-2.5 m, above
    for (const Eigen::Vector3f& c : cb) {
        if (in_a.count(cell_key(c, e))) {
            ++kept;
            continue;
        }
        ++added;
        const auto* v = B.voxel_at(c);
        if (!v) continue;
        std::uint32_t hits = 0;
        for (const auto& h : v->hit_histogram()) hits += h.count;
        by_hits[hits <= 1 ? 0 : hits <= 4 ? 1 : hits <= 19 ? 2 : 3]++;
        const float up = c.z() - column_floor.at(column(c));
        by_height[up < 0.5f ? 0 : up < 2.5f ? 1 : 2]++;
        if (v->flags & maintenance::kGround) ++ground;
        if (v->created() > 0.0 && in_a.size() && v->created() >= A.map_time()) ++created_now;
    }
    const std::size_t gone = in_a.size() - kept;
    std::printf(
        "  maintained voxels %zu -> %zu (%+.2f %%): %zu added (%zu created in the new "
        "sessions), %zu gone\n",
        in_a.size(), cb.size(),
        in_a.empty() ? 0.0
                     : 100.0 * (double(cb.size()) - double(in_a.size())) / double(in_a.size()),
        added, created_now, gone);
    std::printf(
        "  added by hits 0-1 / 2-4 / 5-19 / 20+: %zu / %zu / %zu / %zu; by height over "
        "their 2 m column's lowest <0.5 / 0.5-2.5 / >2.5 m: %zu / %zu / %zu; ground %zu\n",
        by_hits[0], by_hits[1], by_hits[2], by_hits[3], by_height[0], by_height[1], by_height[2],
        ground);
}

}  // namespace ltm::bench
