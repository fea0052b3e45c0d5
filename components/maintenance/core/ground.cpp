#include "maintenance/core/ground.hpp"

#include <cmath>
#include <limits>
#include <unordered_map>

namespace ltm::maintenance {

namespace {
std::uint64_t column_key(int x, int y) {
    return (std::uint64_t(std::uint32_t(x)) << 32) | std::uint64_t(std::uint32_t(y));
}
}  // namespace

std::size_t mark_ground(const GroundConfig& config, ObservationMap& map) {
    const float inv = 1.0f / float(config.column_size);
    std::unordered_map<std::uint64_t, float> lowest;
    lowest.reserve(map.size() / 4 + 1);
    std::vector<Eigen::Vector3f> centres(map.size());
    for (std::uint32_t i = 0; i < map.size(); ++i) {
        centres[i] = map.centre(i);
        const std::uint64_t k = column_key(int(std::floor(centres[i].x() * inv)),
                                           int(std::floor(centres[i].y() * inv)));
        auto [it, inserted] = lowest.emplace(k, centres[i].z());
        if (!inserted && centres[i].z() < it->second) it->second = centres[i].z();
    }
    const float cos_tilt = float(std::cos(config.max_tilt * 3.14159265358979 / 180.0));
    const int n = config.neighbourhood;
    std::size_t ground = 0;
    for (std::uint32_t i = 0; i < map.size(); ++i) {
        const int cx = int(std::floor(centres[i].x() * inv));
        const int cy = int(std::floor(centres[i].y() * inv));
        float low = std::numeric_limits<float>::infinity();
        for (int dy = -n; dy <= n; ++dy) {
            for (int dx = -n; dx <= n; ++dx) {
                const auto it = lowest.find(column_key(cx + dx, cy + dy));
                if (it != lowest.end() && it->second < low) low = it->second;
            }
        }
        bool is_ground = centres[i].z() - low <= float(config.height);
        if (is_ground) {
            const Eigen::Vector3f normal = map.normal(i);
            if (normal.squaredNorm() > 0.5f) {
                is_ground = std::abs(normal.z()) >= cos_tilt;
            } else {  // no plane (few points, or a wall's foot): flat points only
                const registration::VoxelSums s = map.voxel(i).sums(map.voxel_size());
                const float mz = s.sum.z() / std::max(s.weight, 1.0f);
                const float var_z = s.sum_sq(5) / std::max(s.weight, 1.0f) - mz * mz;
                is_ground = var_z <= float(config.flatness * config.flatness);
            }
        }
        ObservedVoxel& v = map.voxel(i);
        if (is_ground) {
            v.flags = std::uint8_t(v.flags | kGround);
            ++ground;
        } else {
            v.flags = std::uint8_t(v.flags & ~kGround);
        }
    }
    return ground;
}

}  // namespace ltm::maintenance
