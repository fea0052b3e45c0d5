#pragma once
// Where objects may stand: road corridors (robot routes, actor paths) that must stay clear and
// the footprints of objects already placed, in a uniform grid for fast queries.
#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <unordered_map>
#include <vector>

#include "simulator/core/geometry2d.hpp"

namespace ltm::sim {

class FreeSpace {
  public:
    explicit FreeSpace(double cell = 8.0) : cell_(cell) {}

    // A corridor of half width `half_width` [m] around the polyline. Roads (robot routes) take
    // the per-query road margin; other corridors (actor paths) the ordinary margin.
    void add_corridor(const Points2& polyline, double half_width, bool road = true);
    // A placed object's footprint; `id` lets it be removed later.
    void add_footprint(const OrientedRect& r, std::uint32_t id);
    void remove_footprint(std::uint32_t id);

    // True when `r` stays `road_margin` [m] off every road corridor and `margin` [m] off every
    // other corridor and every footprint.
    bool is_free(const OrientedRect& r, double road_margin, double margin) const;
    // Distance from p to the nearest road centre line [m], or +inf beyond `search` metres.
    double corridor_distance(const Eigen::Vector2d& p, double search) const;
    // Same, minus that road's half width (negative inside a road corridor).
    double corridor_clearance(const Eigen::Vector2d& p, double search) const;

  private:
    struct Segment {
        Eigen::Vector2d a, b;
        double half_width;
        bool road;
    };
    struct Footprint {
        OrientedRect rect;
        std::uint32_t id;
        bool active;
    };
    using Key = std::int64_t;
    Key key(int ix, int iy) const {
        return (static_cast<Key>(ix) << 32) ^ static_cast<std::uint32_t>(iy);
    }
    int index(double v) const { return static_cast<int>(std::floor(v / cell_)); }
    template <typename F>
    void for_cells(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, F&& f) const;

    double cell_;
    double max_half_width_ = 0.0;
    std::vector<Segment> segments_;
    std::vector<Footprint> footprints_;
    std::unordered_map<Key, std::vector<std::uint32_t>> segment_cells_, footprint_cells_;
};

}  // namespace ltm::sim
