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

Eigen::Vector3i RemovedCells::block(const Eigen::Vector3i& c) {
    Eigen::Vector3i b;
    for (int a = 0; a < 3; ++a) b[a] = c[a] >= 0 ? c[a] / kBlock : -((-c[a] - 1) / kBlock) - 1;
    return b;
}

bool RemovedCells::Set::may_hold(const Eigen::Vector3i& lo, const Eigen::Vector3i& hi) const {
    const Eigen::Vector3i a = block(lo), b = block(hi);
    for (int x = a.x(); x <= b.x(); ++x)
        for (int y = a.y(); y <= b.y(); ++y)
            for (int z = a.z(); z <= b.z(); ++z)
                if (blocks.count(key(Eigen::Vector3i(x, y, z)))) return true;
    return false;
}

std::size_t RemovedCells::memory_bytes() const {
    // A node: the next pointer and the value, in a 32-byte malloc chunk (glibc's minimum).
    constexpr std::size_t kNode = 32;
    std::size_t n = 0;
    for (const Set* set : {&all_, &surface_}) {
        n += (set->cells.bucket_count() + set->blocks.bucket_count()) * sizeof(void*) +
             (set->cells.size() + set->blocks.size()) * kNode;
    }
    return n;
}

std::size_t RemovedCells::add_to(Set& set, const std::vector<Eigen::Vector3f>& centres,
                                 float cell_size) {
    if (!(cell_size > 0.0f) || !std::isfinite(cell_size)) return 0;
    if (size_ == 0.0f) size_ = cell_size;
    std::size_t added = 0;
    for (const Eigen::Vector3f& c : centres) {
        if (!c.allFinite() || c.cwiseAbs().maxCoeff() > 2.0e5f) continue;
        if (set.cells.size() >= capacity_) {
            full_ = true;
            break;
        }
        const Eigen::Vector3i k = cell(c);
        if (set.cells.insert(key(k)).second) {
            ++added;
            ++set.blocks[key(block(k))];
        }
    }
    return added;
}

std::size_t RemovedCells::add(const std::vector<Eigen::Vector3f>& centres, float cell_size) {
    return add_to(all_, centres, cell_size);
}

std::size_t RemovedCells::add_surface(const std::vector<Eigen::Vector3f>& centres,
                                      float cell_size) {
    return add_to(surface_, centres, cell_size);
}

void RemovedCells::erase(const std::vector<Eigen::Vector3f>& centres) {
    if (size_ == 0.0f) return;
    for (const Eigen::Vector3f& c : centres) {
        if (!c.allFinite() || c.cwiseAbs().maxCoeff() > 2.0e5f) continue;
        const Eigen::Vector3i k = cell(c);
        for (Set* set : {&all_, &surface_}) {
            if (set->cells.erase(key(k)) == 0) continue;
            const auto b = set->blocks.find(key(block(k)));
            if (b != set->blocks.end() && --b->second == 0) set->blocks.erase(b);
        }
    }
}

bool RemovedCells::covers(const Eigen::Vector3f& p) const {
    if (all_.cells.empty() || !p.allFinite() || p.cwiseAbs().maxCoeff() > 2.0e5f) return false;
    const Eigen::Vector3f q = p / size_;
    const Eigen::Vector3i c = q.array().floor().cast<int>();
    // The neighbour on the side of p along each axis (p is within half a cell of it).
    Eigen::Vector3i side;
    for (int a = 0; a < 3; ++a) side[a] = q[a] - float(c[a]) < 0.5f ? -1 : 1;
    if (!all_.may_hold(c.cwiseMin(c + side), c.cwiseMax(c + side))) return false;
    for (int i = 0; i < 8; ++i) {
        Eigen::Vector3i n = c;
        for (int a = 0; a < 3; ++a) {
            if (i & (1 << a)) n[a] += side[a];
        }
        if (all_.cells.count(key(n))) return true;
    }
    return false;
}

template <class Keep>
bool RemovedCells::any_within(const Set& set, const Eigen::Vector3f& p, float reach,
                              Keep keep) const {
    const Eigen::Vector3i lo = ((p.array() - reach) / size_).floor().cast<int>();
    const Eigen::Vector3i hi = ((p.array() + reach) / size_).floor().cast<int>();
    if (!set.may_hold(lo, hi)) return false;
    const float r2 = reach * reach;
    for (int x = lo.x(); x <= hi.x(); ++x)
        for (int y = lo.y(); y <= hi.y(); ++y)
            for (int z = lo.z(); z <= hi.z(); ++z) {
                const Eigen::Vector3i c(x, y, z);
                const Eigen::Vector3f d = (c.cast<float>().array() + 0.5f) * size_ - p.array();
                if (d.squaredNorm() <= r2 && keep(d) && set.cells.count(key(c))) return true;
            }
    return false;
}

bool RemovedCells::covers(const Eigen::Vector3f& p, float radius) const {
    if (covers(p)) return true;
    if (!(radius > 0.0f) || all_.cells.empty() || !p.allFinite() ||
        p.cwiseAbs().maxCoeff() > 2.0e5f)
        return false;
    return any_within(all_, p, radius, [](const Eigen::Vector3f&) { return true; });
}

bool RemovedCells::surface_near(const Eigen::Vector3f& p, const Eigen::Vector3f& n, float reach,
                                float band) const {
    if (surface_.cells.empty() || !(reach > 0.0f) || !(band >= 0.0f) || !p.allFinite() ||
        !n.allFinite() || p.cwiseAbs().maxCoeff() > 2.0e5f)
        return false;
    return any_within(surface_, p, reach,
                      [&](const Eigen::Vector3f& d) { return std::abs(d.dot(n)) <= band; });
}

}  // namespace ltm::mapping
