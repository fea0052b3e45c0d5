#include "simulator/cli/scan_stats.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace ltm::sim::cli {
namespace {

double percentile(std::vector<double> v, double q) {
    if (v.empty()) return 0.0;
    const std::size_t k = static_cast<std::size_t>(q * (v.size() - 1));
    std::nth_element(v.begin(), v.begin() + static_cast<long>(k), v.end());
    return v[k];
}

}  // namespace

std::vector<int> rings_from_order(const common::PointCloud& cloud) {
    std::vector<int> rings(cloud.size(), 0);
    int ring = 0;
    double prev = 0.0;
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const double az = std::atan2(cloud.points[i].y(), cloud.points[i].x());
        if (i > 0 && prev < 0.0 && prev > -M_PI / 2 && az >= 0.0 && az < M_PI / 2) ++ring;
        rings[i] = ring;
        prev = az;
    }
    return rings;
}

ScanStats scan_stats(const common::PointCloud& cloud, const std::vector<double>& range_edges) {
    ScanStats s;
    s.points = cloud.size();
    s.range_edges = range_edges;
    s.range_fraction.assign(range_edges.size(), 0.0);
    const std::vector<int> rings = rings_from_order(cloud);
    const int n_rings = rings.empty() ? 0 : rings.back() + 1;
    s.ring_points.assign(static_cast<std::size_t>(n_rings), 0.0);
    std::vector<std::vector<double>> elev(static_cast<std::size_t>(n_rings));
    std::vector<double> ranges, intens;
    ranges.reserve(cloud.size());
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const Eigen::Vector3f& p = cloud.points[i];
        const double r = p.norm();
        ranges.push_back(r);
        s.ring_points[static_cast<std::size_t>(rings[i])] += 1.0;
        elev[static_cast<std::size_t>(rings[i])].push_back(std::atan2(p.z(), p.head<2>().norm()) *
                                                           180.0 / M_PI);
        std::size_t bin = 0;
        while (bin + 1 < range_edges.size() && r >= range_edges[bin + 1]) ++bin;
        s.range_fraction[bin] += 1.0;
        if (cloud.has_intensity()) intens.push_back(cloud.intensity[i]);
    }
    for (auto& f : s.range_fraction) f /= std::max<std::size_t>(1, cloud.size());
    for (const auto& e : elev) s.ring_elevation.push_back(percentile(e, 0.5));
    s.range_median = percentile(ranges, 0.5);
    for (const double q : {0.1, 0.25, 0.5, 0.75, 0.9})
        s.intensity_pct.push_back(percentile(intens, q));
    return s;
}

ScanStats average_stats(const std::vector<ScanStats>& stats) {
    ScanStats m;
    if (stats.empty()) return m;
    std::size_t rings = 0;
    for (const auto& s : stats) rings = std::max(rings, s.ring_points.size());
    m.ring_points.assign(rings, 0.0);
    m.ring_elevation.assign(rings, 0.0);
    m.range_edges = stats[0].range_edges;
    m.range_fraction.assign(m.range_edges.size(), 0.0);
    m.intensity_pct.assign(stats[0].intensity_pct.size(), 0.0);
    const double n = static_cast<double>(stats.size());
    double points = 0;
    for (const auto& s : stats) {
        points += static_cast<double>(s.points) / n;
        m.range_median += s.range_median / n;
        for (std::size_t r = 0; r < s.ring_points.size(); ++r) {
            m.ring_points[r] += s.ring_points[r] / n;
            m.ring_elevation[r] += s.ring_elevation[r] / n;
        }
        for (std::size_t b = 0; b < s.range_fraction.size() && b < m.range_fraction.size(); ++b)
            m.range_fraction[b] += s.range_fraction[b] / n;
        for (std::size_t q = 0; q < s.intensity_pct.size() && q < m.intensity_pct.size(); ++q)
            m.intensity_pct[q] += s.intensity_pct[q] / n;
    }
    m.points = static_cast<std::size_t>(std::lround(points));
    return m;
}

std::string compare_table(const std::vector<ScanStats>& cols,
                          const std::vector<std::string>& names) {
    std::string out;
    char cell[64];
    auto row = [&](const std::string& label, auto value) {
        std::snprintf(cell, sizeof cell, "%-24s", label.c_str());
        out += cell;
        for (std::size_t c = 0; c < cols.size(); ++c) out += value(cols[c]);
        out += "\n";
    };
    auto num = [&](const char* fmt, double v) {
        std::snprintf(cell, sizeof cell, fmt, v);
        return std::string(cell);
    };
    std::snprintf(cell, sizeof cell, "%-24s", "");
    out += cell;
    for (const auto& name : names) {
        std::snprintf(cell, sizeof cell, "%16s", name.c_str());
        out += cell;
    }
    out += "\n";
    row("points a scan (mean)",
        [&](const ScanStats& s) { return num("%16.0f", double(s.points)); });
    row("rings found",
        [&](const ScanStats& s) { return num("%16.0f", double(s.ring_points.size())); });
    row("median range [m]", [&](const ScanStats& s) { return num("%16.1f", s.range_median); });
    const char* q[] = {"intensity p10", "intensity p25", "intensity p50", "intensity p75",
                       "intensity p90"};
    for (std::size_t k = 0; k < 5; ++k) {
        row(q[k], [&](const ScanStats& s) {
            return num("%16.3f", k < s.intensity_pct.size() ? s.intensity_pct[k] : 0.0);
        });
    }
    out += "\nrange histogram (share of points)\n";
    const std::vector<double>& edges = cols.empty() ? std::vector<double>() : cols[0].range_edges;
    for (std::size_t b = 0; b < edges.size(); ++b) {
        char label[64];
        if (b + 1 < edges.size()) {
            std::snprintf(label, sizeof label, "  %5.1f - %5.1f m", edges[b], edges[b + 1]);
        } else {
            std::snprintf(label, sizeof label, "  >= %5.1f m", edges[b]);
        }
        row(label, [&](const ScanStats& s) {
            return num("%15.1f%%", b < s.range_fraction.size() ? 100 * s.range_fraction[b] : 0.0);
        });
    }
    out += "\npoints per ring | median elevation [deg]\n";
    std::size_t rings = 0;
    for (const auto& s : cols) rings = std::max(rings, s.ring_points.size());
    for (std::size_t r = 0; r < rings; ++r) {
        std::snprintf(cell, sizeof cell, "  ring %2zu", r);
        out += std::string(cell) + std::string(15, ' ');
        for (const auto& s : cols)
            out += num("%9.0f", r < s.ring_points.size() ? s.ring_points[r] : 0.0);
        out += "  |";
        for (const auto& s : cols)
            out += num("%8.2f", r < s.ring_elevation.size() ? s.ring_elevation[r] : 0.0);
        out += "\n";
    }
    return out;
}

}  // namespace ltm::sim::cli
