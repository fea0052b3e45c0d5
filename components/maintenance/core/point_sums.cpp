#include "maintenance/core/point_sums.hpp"

#include <algorithm>
#include <cmath>

namespace ltm::maintenance {

void PointSums::add(const Eigen::Vector3f& q, float voxel_size) {
    if (count >= kMaxPoints || !q.allFinite() || !(voxel_size > 0.0f)) return;
    const float scale = kUnitsPerVoxel / voxel_size;
    int u[3];
    for (int k = 0; k < 3; ++k) u[k] = std::clamp(int(std::lround(q[k] * scale)), -127, 127);
    for (int k = 0; k < 3; ++k) sum[std::size_t(k)] = std::int16_t(sum[std::size_t(k)] + u[k]);
    const int products[6] = {u[0] * u[0], u[0] * u[1], u[0] * u[2],
                             u[1] * u[1], u[1] * u[2], u[2] * u[2]};
    for (int k = 0; k < 6; ++k) {
        const int p = int(std::lround(float(products[k]) / kSquareUnit));
        sum_sq[std::size_t(k)] = std::int16_t(sum_sq[std::size_t(k)] + p);
    }
    ++count;
}

registration::VoxelSums PointSums::sums(float voxel_size) const {
    registration::VoxelSums s;
    const float unit = voxel_size / kUnitsPerVoxel;
    s.weight = float(count);
    for (int k = 0; k < 3; ++k) s.sum[k] = float(sum[std::size_t(k)]) * unit;
    for (int k = 0; k < 6; ++k)
        s.sum_sq[k] = float(sum_sq[std::size_t(k)]) * kSquareUnit * unit * unit;
    return s;
}

}  // namespace ltm::maintenance
