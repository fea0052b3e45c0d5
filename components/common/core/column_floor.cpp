#include "common/core/column_floor.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ltm::common {

ColumnFloor::ColumnFloor(float column_size, std::size_t expected_columns)
    : inv_size_(1.0f / column_size) {
    lowest_.reserve(expected_columns);
}

std::uint64_t ColumnFloor::key(int x, int y) {
    return (std::uint64_t(std::uint32_t(x)) << 32) | std::uint64_t(std::uint32_t(y));
}

Eigen::Vector2i ColumnFloor::column(const Eigen::Vector3f& p) const {
    return Eigen::Vector2i(int(std::floor(p.x() * inv_size_)), int(std::floor(p.y() * inv_size_)));
}

void ColumnFloor::add(const Eigen::Vector3f& p) {
    if (!p.allFinite()) return;
    const Eigen::Vector2i c = column(p);
    auto [it, added] = lowest_.emplace(key(c.x(), c.y()), p.z());
    if (!added) it->second = std::min(it->second, p.z());
}

float ColumnFloor::lowest_around(const Eigen::Vector3f& p, int cells) const {
    float low = std::numeric_limits<float>::infinity();
    if (!p.allFinite()) return low;
    const Eigen::Vector2i c = column(p);
    for (int dy = -cells; dy <= cells; ++dy) {
        for (int dx = -cells; dx <= cells; ++dx) {
            const auto it = lowest_.find(key(c.x() + dx, c.y() + dy));
            if (it != lowest_.end()) low = std::min(low, it->second);
        }
    }
    return low;
}

}  // namespace ltm::common
