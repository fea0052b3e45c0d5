#include "maintenance/core/reach_down.hpp"

#include <cmath>

namespace ltm::maintenance {

namespace {

// No view of it (hit or seen through) since the session began.
bool unseen_since(const ObservedVoxel& v, std::int32_t session_slot) {
    const VoxelHistory::Entries e = v.history.entries();
    return e.n == 0 || e.e[std::size_t(e.n - 1)].slot < session_slot;
}

}  // namespace

std::vector<std::uint32_t> reach_down(const MaintenanceConfig& config, const ObservationMap& map,
                                      double session_start, std::vector<bool>* remove) {
    std::vector<std::uint32_t> added;
    if (config.change.reach_down <= 0.0 || map.empty()) return added;
    std::vector<bool>& out = *remove;
    const float step = map.voxel_size();
    const int cells = int(std::floor(config.change.reach_down / double(step) + 1e-6));
    const auto session_slot = std::int32_t(std::floor(session_start / config.slot));
    const auto before = [&](const ObservedVoxel& v) { return v.created() < session_start; };
    std::vector<std::uint32_t> seeds;
    for (std::uint32_t i = 0; i < map.size(); ++i)
        if (out[i] && before(map.voxel(i))) seeds.push_back(i);
    for (const std::uint32_t seed : seeds) {
        Eigen::Vector3f p = map.cell_centre(seed);
        for (int k = 0; k < cells; ++k) {
            p.z() -= step;
            const std::uint32_t b = map.find(p);
            if (b == ObservationMap::kNone) break;
            if (out[b]) continue;  // removed already: the walk goes on below it
            const ObservedVoxel& v = map.voxel(b);
            if ((v.flags & kGround) || !before(v) || v.last_point() >= session_start ||
                !unseen_since(v, session_slot))
                break;
            out[b] = true;
            added.push_back(b);
        }
    }
    return added;
}

}  // namespace ltm::maintenance
