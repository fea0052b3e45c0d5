#include "simulator/core/free_space.hpp"

#include <algorithm>
#include <cmath>

namespace ltm::sim {

template <typename F>
void FreeSpace::for_cells(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, F&& f) const {
    for (int ix = index(lo.x()); ix <= index(hi.x()); ++ix) {
        for (int iy = index(lo.y()); iy <= index(hi.y()); ++iy) f(key(ix, iy));
    }
}

void FreeSpace::add_corridor(const Points2& polyline, double half_width, bool road) {
    max_half_width_ = std::max(max_half_width_, half_width);
    for (std::size_t i = 0; i + 1 < polyline.size(); ++i) {
        // Long segments are split so each one touches few cells.
        const Eigen::Vector2d a = polyline[i], b = polyline[i + 1];
        const int pieces = std::max(1, static_cast<int>(std::ceil((b - a).norm() / cell_)));
        for (int k = 0; k < pieces; ++k) {
            const Eigen::Vector2d p = a + (b - a) * (double(k) / pieces);
            const Eigen::Vector2d q = a + (b - a) * (double(k + 1) / pieces);
            const auto id = static_cast<std::uint32_t>(segments_.size());
            segments_.push_back({p, q, half_width, road});
            const Eigen::Vector2d pad = Eigen::Vector2d::Constant(half_width);
            for_cells(p.cwiseMin(q) - pad, p.cwiseMax(q) + pad,
                      [&](Key k2) { segment_cells_[k2].push_back(id); });
        }
    }
}

void FreeSpace::add_footprint(const OrientedRect& r, std::uint32_t id) {
    const auto slot = static_cast<std::uint32_t>(footprints_.size());
    footprints_.push_back({r, id, true});
    Eigen::Vector2d lo = r.corner(0), hi = r.corner(0);
    for (int k = 1; k < 4; ++k) {
        lo = lo.cwiseMin(r.corner(k));
        hi = hi.cwiseMax(r.corner(k));
    }
    for_cells(lo, hi, [&](Key k) { footprint_cells_[k].push_back(slot); });
}

void FreeSpace::remove_footprint(std::uint32_t id) {
    for (auto& f : footprints_) {
        if (f.id == id) f.active = false;
    }
}

bool FreeSpace::is_free(const OrientedRect& r, double road_margin, double margin) const {
    Eigen::Vector2d lo = r.corner(0), hi = r.corner(0);
    for (int k = 1; k < 4; ++k) {
        lo = lo.cwiseMin(r.corner(k));
        hi = hi.cwiseMax(r.corner(k));
    }
    const Eigen::Vector2d pad =
        Eigen::Vector2d::Constant(std::max(margin, road_margin) + max_half_width_);
    bool free = true;
    for_cells(lo - pad, hi + pad, [&](Key k) {
        if (!free) return;
        if (const auto it = segment_cells_.find(k); it != segment_cells_.end()) {
            for (const std::uint32_t s : it->second) {
                const Segment& seg = segments_[s];
                if (segment_rect_distance(seg.a, seg.b, r) <
                    seg.half_width + (seg.road ? road_margin : margin)) {
                    free = false;
                    return;
                }
            }
        }
        if (const auto it = footprint_cells_.find(k); it != footprint_cells_.end()) {
            for (const std::uint32_t f : it->second) {
                if (footprints_[f].active && rects_overlap(footprints_[f].rect, r, margin * 0.5)) {
                    free = false;
                    return;
                }
            }
        }
    });
    return free;
}

double FreeSpace::corridor_distance(const Eigen::Vector2d& p, double search) const {
    double best = std::numeric_limits<double>::infinity();
    const Eigen::Vector2d pad = Eigen::Vector2d::Constant(search);
    for_cells(p - pad, p + pad, [&](Key k) {
        if (const auto it = segment_cells_.find(k); it != segment_cells_.end()) {
            for (const std::uint32_t s : it->second) {
                if (!segments_[s].road) continue;
                best = std::min(best, point_segment_distance(p, segments_[s].a, segments_[s].b));
            }
        }
    });
    return best <= search ? best : std::numeric_limits<double>::infinity();
}

double FreeSpace::corridor_clearance(const Eigen::Vector2d& p, double search) const {
    double best = std::numeric_limits<double>::infinity();
    const Eigen::Vector2d pad = Eigen::Vector2d::Constant(search);
    for_cells(p - pad, p + pad, [&](Key k) {
        if (const auto it = segment_cells_.find(k); it != segment_cells_.end()) {
            for (const std::uint32_t s : it->second) {
                const Segment& seg = segments_[s];
                if (!seg.road) continue;
                best = std::min(best, point_segment_distance(p, seg.a, seg.b) - seg.half_width);
            }
        }
    });
    return best <= search ? best : std::numeric_limits<double>::infinity();
}

}  // namespace ltm::sim
