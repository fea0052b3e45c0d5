#include "mapping/core/removed_cells.hpp"

#include <cmath>

namespace ltm::mapping {

std::uint64_t RemovedCells::key(const Eigen::Vector3i& c) {
    // 21 bits an axis (+-1 M cells: +-262 km at 0.25 m).
    auto pack = [](int v) { return std::uint64_t(std::uint32_t(v + (1 << 20)) & 0x1FFFFFu); };
    return pack(c.x()) | (pack(c.y()) << 21) | (pack(c.z()) << 42);
}

Eigen::Vector3i RemovedCells::cell(const Eigen::Vector3f& p) const {
    return (p / size_).array().floor().cast<int>();
}

std::size_t RemovedCells::add(const std::vector<Eigen::Vector3f>& centres, float cell_size) {
    if (!(cell_size > 0.0f) || !std::isfinite(cell_size)) return 0;
    if (size_ == 0.0f) size_ = cell_size;
    std::size_t added = 0;
    for (const Eigen::Vector3f& c : centres) {
        if (!c.allFinite() || c.cwiseAbs().maxCoeff() > 2.0e5f) continue;
        if (cells_.size() >= capacity_) {
            full_ = true;
            break;
        }
        added += cells_.insert(key(cell(c))).second;
    }
    return added;
}

void RemovedCells::erase(const std::vector<Eigen::Vector3f>& centres) {
    if (size_ == 0.0f) return;
    for (const Eigen::Vector3f& c : centres) {
        if (c.allFinite() && c.cwiseAbs().maxCoeff() <= 2.0e5f) cells_.erase(key(cell(c)));
    }
}

bool RemovedCells::covers(const Eigen::Vector3f& p) const {
    if (cells_.empty() || !p.allFinite() || p.cwiseAbs().maxCoeff() > 2.0e5f) return false;
    const Eigen::Vector3f q = p / size_;
    const Eigen::Vector3i c = q.array().floor().cast<int>();
    // The neighbour on the side of p along each axis (p is within half a cell of it).
    Eigen::Vector3i side;
    for (int a = 0; a < 3; ++a) side[a] = q[a] - float(c[a]) < 0.5f ? -1 : 1;
    for (int i = 0; i < 8; ++i) {
        Eigen::Vector3i n = c;
        for (int a = 0; a < 3; ++a) {
            if (i & (1 << a)) n[a] += side[a];
        }
        if (cells_.count(key(n))) return true;
    }
    return false;
}

bool RemovedCells::covers(const Eigen::Vector3f& p, float radius) const {
    if (covers(p)) return true;
    if (!(radius > 0.0f) || cells_.empty() || !p.allFinite() || p.cwiseAbs().maxCoeff() > 2.0e5f)
        return false;
    const Eigen::Vector3i lo = ((p.array() - radius) / size_).floor().cast<int>();
    const Eigen::Vector3i hi = ((p.array() + radius) / size_).floor().cast<int>();
    const float r2 = radius * radius;
    for (int x = lo.x(); x <= hi.x(); ++x)
        for (int y = lo.y(); y <= hi.y(); ++y)
            for (int z = lo.z(); z <= hi.z(); ++z) {
                const Eigen::Vector3i c(x, y, z);
                const Eigen::Vector3f centre = (c.cast<float>().array() + 0.5f) * size_;
                if ((centre - p).squaredNorm() <= r2 && cells_.count(key(c))) return true;
            }
    return false;
}

}  // namespace ltm::mapping
