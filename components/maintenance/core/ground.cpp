#include "maintenance/core/ground.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "common/core/column_floor.hpp"

namespace ltm::maintenance {

std::size_t mark_ground(const GroundConfig& config, ObservationMap& map) {
    common::ColumnFloor floor(float(config.column_size), map.size() / 4 + 1);
    std::vector<Eigen::Vector3f> centres(map.size());
    for (std::uint32_t i = 0; i < map.size(); ++i) {
        centres[i] = map.centre(i);
        floor.add(centres[i]);
    }
    const float cos_tilt = float(std::cos(config.max_tilt * 3.14159265358979 / 180.0));
    std::size_t ground = 0;
    for (std::uint32_t i = 0; i < map.size(); ++i) {
        const float low = floor.lowest_around(centres[i], config.neighbourhood);
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
