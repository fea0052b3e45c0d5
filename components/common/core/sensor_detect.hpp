#pragma once
// The sensor class from the scans themselves (`preset: auto`): a scan's shape (rings, vertical and
// horizontal field of view, point count, ranges) mapped to one of the sensor presets, with the
// reason in one line. What fits no preset is refused, not guessed: the detector then names the
// fallback it uses ("unknown sensor (...), using hdl64"). No I/O, no middleware.
//   The rules (classify_scan): a horizontal field under 180 deg is a narrow (Livox type) sensor;
// a spinning one (270 deg or more) is told by its rings: 12-24 a VLP-16 (none below -19 deg), 25-44
// a VLP-32C, 45-80 a 64-beam sensor, an Ouster OS1-64 when it sees above +8 deg (an HDL-64E's top
// beam is +2 deg) or its fullest ring has under 1,400 points (1,024 columns against the HDL-64E's
// ~2,000), else an HDL-64E. Rings come from the scan's ring field when it has one, else from the
// elevation histogram (see measure_scan).
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common/core/point_cloud.hpp"
#include "common/core/sensor_preset.hpp"

namespace ltm::common {

// The value of a component's `preset` that asks for detection.
inline constexpr const char* kAutoPreset = "auto";
// The place, loop and localisation settings `auto` gives a component that sees no scans (the
// mapping) or sets them before its first scan (the localisation's map): the spinning sensors',
// the same in hdl64, vlp32, vlp16 and os1-64 (sensor_preset_test checks it). A narrow sensor must
// be named there.
inline constexpr SensorPreset kAutoSpinningPreset = SensorPreset::kHdl64;

struct ScanShape {
    std::size_t points = 0;      // finite points
    std::size_t non_finite = 0;  // NaN or infinite points (ignored)
    int rings = 0;               // beams: distinct ring values, or elevation clusters
    bool rings_from_field = false;
    bool rings_from_order = false;  // counted as scan lines in the points' order
    std::size_t fullest_ring = 0;   // points of the most populated ring
    double min_elevation_deg = 0;   // 0.5 % and 99.5 % quantiles of the points' elevations
    double max_elevation_deg = 0;
    double horizontal_fov_deg = 0;           // 360 minus the widest azimuth gap (0.5 deg bins)
    double median_range = 0, max_range = 0;  // [m]
};

// The shape of one scan (sensor frame). `rings`: the scan's ring field (one per point) when it has
// one, else null: rings are then the scan lines of a cloud stored ring by ring (8 or more azimuth
// jumps of over 270 deg in the points' order), else clusters of the elevations of the points 2 m
// or more away (0.05 deg bins; a bin counts with at least 0.1 % of those points, or 3).
ScanShape measure_scan(const PointCloud& cloud, const std::vector<std::uint16_t>* rings = nullptr);

struct SensorGuess {
    std::optional<SensorPreset> preset;  // empty: no preset fits
    std::string reason;                  // one line: the figures and the rule that decided
};

// The preset of a scan of this shape, or none (with why).
SensorGuess classify_scan(const ScanShape& shape);

struct SensorDetectConfig {
    int max_scans = 5;  // scans looked at before giving up on an unclassifiable sensor
    SensorPreset fallback = SensorPreset::kHdl64;  // used then (every module's defaults)
};

// Decides on the first scan that classifies; after max_scans scans none did: the fallback.
class SensorDetector {
  public:
    explicit SensorDetector(SensorDetectConfig config = {}) : config_(config) {}

    // Looks at a scan; true when decided (with this scan or before).
    bool add(const PointCloud& cloud, const std::vector<std::uint16_t>* rings = nullptr);
    // Decides now with what was seen (the fallback if no scan classified).
    void finish();

    bool decided() const { return preset_.has_value(); }
    SensorPreset preset() const { return preset_.value_or(config_.fallback); }
    bool detected() const { return detected_; }  // false: the fallback
    int scans_seen() const { return seen_; }
    // "preset vlp16 from scan 1: ..." or "unknown sensor (...), using hdl64 after 5 scans".
    const std::string& line() const { return line_; }

  private:
    SensorDetectConfig config_;
    std::optional<SensorPreset> preset_;
    bool detected_ = false;
    int seen_ = 0;
    std::string last_reason_ = "no scan";
    std::string line_;
};

}  // namespace ltm::common
