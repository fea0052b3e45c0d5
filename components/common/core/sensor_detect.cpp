#include "common/core/sensor_detect.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

namespace ltm::common {
namespace {

constexpr double kRad = 180.0 / M_PI;
constexpr double kRingMinRange = 2.0;     // [m] points clustered into rings
constexpr double kElevationBin = 0.05;    // [deg]
constexpr int kMinGapBins = 2;            // empty bins between two rings
constexpr std::size_t kMinPoints = 1000;  // fewer: no class
constexpr double kAzimuthBin = 0.5;       // [deg]

double quantile(std::vector<double>& v, double q) {
    if (v.empty()) return 0.0;
    const auto k = static_cast<std::size_t>(q * double(v.size() - 1));
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
    return v[k];
}

// Rings as runs of elevation bins holding enough points, with their populations.
std::vector<std::size_t> elevation_clusters(const std::vector<double>& elevations) {
    const int bins = int(std::lround(180.0 / kElevationBin));
    std::vector<std::size_t> hist(static_cast<std::size_t>(bins), 0);
    for (double e : elevations) {
        const int b = std::clamp(int((e + 90.0) / kElevationBin), 0, bins - 1);
        ++hist[static_cast<std::size_t>(b)];
    }
    const std::size_t enough = std::max<std::size_t>(3, elevations.size() / 1000);
    std::vector<std::size_t> clusters;
    int gap = kMinGapBins;
    for (std::size_t count : hist) {
        if (count >= enough) {
            if (gap >= kMinGapBins) clusters.push_back(0);
            clusters.back() += count;
            gap = 0;
        } else {
            ++gap;
        }
    }
    return clusters;
}

// Scan lines in the points' order: a cloud stored ring by ring (KITTI's, the simulator's) sweeps
// the azimuth once a ring, so each ring has one jump of nearly a full turn (at its +-180 deg
// crossing or where the next ring starts). Populations of the lines; one line: not ring by ring.
std::vector<std::size_t> scan_lines(const std::vector<double>& azimuths) {
    std::vector<std::size_t> lines(azimuths.empty() ? 0 : 1, 0);
    for (std::size_t i = 0; i < azimuths.size(); ++i) {
        if (i > 0 && std::abs(azimuths[i] - azimuths[i - 1]) > 270.0) lines.push_back(0);
        ++lines.back();
    }
    return lines;
}

std::string describe(const ScanShape& s) {
    char text[240];
    std::snprintf(text, sizeof text,
                  "%zu points, %d rings%s, elevation %+.1f to %+.1f deg, %.0f deg around, "
                  "ranges median %.1f max %.0f m",
                  s.points, s.rings,
                  s.rings_from_field   ? " (ring field)"
                  : s.rings_from_order ? " (scan lines)"
                                       : " (elevations)",
                  s.min_elevation_deg, s.max_elevation_deg, s.horizontal_fov_deg, s.median_range,
                  s.max_range);
    return text;
}

}  // namespace

ScanShape measure_scan(const PointCloud& cloud, const std::vector<std::uint16_t>* rings) {
    ScanShape s;
    if (rings && rings->size() != cloud.size()) rings = nullptr;  // not one per point: unused
    std::vector<double> elevations, ranges, far_elevations, azimuths;
    std::vector<char> azimuth(static_cast<std::size_t>(360.0 / kAzimuthBin), 0);
    std::set<std::uint16_t> ring_values;
    std::vector<std::size_t> ring_counts;
    elevations.reserve(cloud.size());
    ranges.reserve(cloud.size());
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const Eigen::Vector3f& p = cloud.points[i];
        if (!p.allFinite()) {
            ++s.non_finite;
            continue;
        }
        const double r = p.norm(), horizontal = std::hypot(double(p.x()), double(p.y()));
        if (r < 1e-3) continue;  // a return at the origin: no direction
        ++s.points;
        ranges.push_back(r);
        const double e = std::atan2(double(p.z()), horizontal) * kRad;
        elevations.push_back(e);
        if (r >= kRingMinRange) far_elevations.push_back(e);
        const double a = std::atan2(double(p.y()), double(p.x())) * kRad + 180.0;  // [0, 360]
        azimuths.push_back(a);
        azimuth[std::min(azimuth.size() - 1, static_cast<std::size_t>(a / kAzimuthBin))] = 1;
        if (rings) {
            const std::uint16_t ring = (*rings)[i];
            ring_values.insert(ring);
            if (ring >= ring_counts.size()) ring_counts.resize(ring + 1u, 0);
            ++ring_counts[ring];
        }
    }
    if (s.points == 0) return s;
    s.min_elevation_deg = quantile(elevations, 0.005);
    s.max_elevation_deg = quantile(elevations, 0.995);
    s.median_range = quantile(ranges, 0.5);
    s.max_range = quantile(ranges, 0.999);
    // The widest circular run of empty azimuth bins.
    std::size_t widest = 0, run = 0;
    for (std::size_t k = 0; k < 2 * azimuth.size(); ++k) {
        run = azimuth[k % azimuth.size()] ? 0 : run + 1;
        widest = std::max(widest, std::min(run, azimuth.size()));
    }
    s.horizontal_fov_deg = 360.0 - double(widest) * kAzimuthBin;
    if (rings) {
        s.rings = int(ring_values.size());
        s.rings_from_field = true;
        s.fullest_ring = *std::max_element(ring_counts.begin(), ring_counts.end());
    } else if (const std::vector<std::size_t> lines = scan_lines(azimuths); lines.size() >= 8) {
        // Stored ring by ring: the lines are the rings (elevations merge the HDL-64E's 1/3 deg
        // rings, whose beams start 0.1-0.14 m apart in height: KITTI's 64 looked like 17).
        s.rings = int(lines.size());
        s.rings_from_order = true;
        s.fullest_ring = *std::max_element(lines.begin(), lines.end());
    } else {
        const std::vector<std::size_t> clusters = elevation_clusters(far_elevations);
        s.rings = int(clusters.size());
        if (!clusters.empty()) s.fullest_ring = *std::max_element(clusters.begin(), clusters.end());
    }
    return s;
}

SensorGuess classify_scan(const ScanShape& s) {
    SensorGuess g;
    const std::string figures = describe(s);
    auto pick = [&](SensorPreset p, const std::string& rule) {
        g.preset = p;
        g.reason = std::string(to_string(p)) + " (" + sensor_preset_row(p).sensor +
                   "): " + figures + "; " + rule;
        return g;
    };
    auto refuse = [&](const std::string& why) {
        g.reason = why + ": " + figures;
        return g;
    };
    if (s.points < kMinPoints) return refuse("too few points to tell (under 1000)");
    const double vertical = s.max_elevation_deg - s.min_elevation_deg;
    if (s.horizontal_fov_deg < 180.0) {
        if (vertical > 100.0) return refuse("a narrow view but over 100 deg high");
        return pick(SensorPreset::kNarrow, "under 180 deg around: a narrow (Livox type) view");
    }
    if (s.horizontal_fov_deg < 270.0) return refuse("neither narrow nor spinning (180-270 deg)");
    // The lowest beams: a VLP-16's -15 deg, the others' -22.5 to -25 deg (4 deg for a tilt).
    if (s.rings >= 12 && s.rings <= 24) {
        if (s.min_elevation_deg < -19.0)
            return refuse("12-24 rings but down to below -19 deg (a VLP-16 reaches -15 deg)");
        return pick(SensorPreset::kVlp16, "12-24 rings");
    }
    if (s.rings >= 25 && s.rings <= 44) return pick(SensorPreset::kVlp32, "25-44 rings");
    if (s.rings >= 45 && s.rings <= 80) {
        if (s.max_elevation_deg > 8.0)
            return pick(SensorPreset::kOs1_64, "45-80 rings seeing above +8 deg");
        if (s.fullest_ring < 1400)
            return pick(SensorPreset::kOs1_64, "45-80 rings of under 1400 points each");
        return pick(SensorPreset::kHdl64, "45-80 rings, none above +8 deg, 1400+ points a ring");
    }
    return refuse("a spinning sensor with a ring count no preset has");
}

bool SensorDetector::add(const PointCloud& cloud, const std::vector<std::uint16_t>* rings) {
    if (decided()) return true;
    ++seen_;
    const SensorGuess g = classify_scan(measure_scan(cloud, rings));
    if (g.preset) {
        preset_ = g.preset;
        detected_ = true;
        line_ = "sensor preset " + g.reason + " (scan " + std::to_string(seen_) + ")";
        return true;
    }
    last_reason_ = g.reason;
    if (seen_ >= config_.max_scans) finish();
    return decided();
}

void SensorDetector::finish() {
    if (decided()) return;
    preset_ = config_.fallback;
    detected_ = false;
    line_ = "unknown sensor (" + last_reason_ + "), using " + to_string(config_.fallback) +
            " after " + std::to_string(seen_) + " scan(s)";
}

}  // namespace ltm::common
