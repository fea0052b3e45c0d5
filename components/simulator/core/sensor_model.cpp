#include "simulator/core/sensor_model.hpp"

#include <algorithm>
#include <cmath>

namespace ltm::sim {
namespace {

constexpr double kDeg = M_PI / 180.0;

Eigen::Vector3f direction(double azimuth_deg, double elevation_deg) {
    const double a = azimuth_deg * kDeg, e = elevation_deg * kDeg;
    return Eigen::Vector3f(float(std::cos(e) * std::cos(a)), float(std::cos(e) * std::sin(a)),
                           float(std::sin(e)));
}

}  // namespace

bool make_sensor_preset(const std::string& name, SensorConfig& c) {
    c = SensorConfig{};
    c.model = name;
    if (name == "hdl64e") {
        // Velodyne HDL-64E S2 as on the KITTI car: upper block +2 to -8.33 deg in 1/3 deg steps,
        // lower block -8.83 to -24.8 deg; 2083 firings a turn at 10 Hz (0.173 deg). The lasers
        // sit above the frame origin (upper block higher): KITTI's ground rings appear 0.5-1.1
        // deg flatter than the beam angles, which these offsets reproduce.
        for (int i = 0; i < 32; ++i) c.elevations_deg.push_back(2.0 - i / 3.0);
        for (int i = 0; i < 32; ++i) c.elevations_deg.push_back(-8.833 - i * (24.8 - 8.833) / 31.0);
        for (int i = 0; i < 64; ++i) c.beam_origin_z.push_back(i < 32 ? 0.14 : 0.10);
        c.columns = 2083;
        c.min_range = 1.0;
        c.max_range = 120.0;
        c.range_at_10pct = 50.0;
        c.height = 1.73;
        return true;
    }
    if (name == "vlp32c") {
        // Velodyne VLP-32C: 32 beams from +15 to -25 deg, dense around the horizon; 0.2 deg.
        c.elevations_deg = {15.0,   10.333, 7.0,    4.667,  3.333,  2.333,  1.667,   1.333,
                            1.0,    0.667,  0.333,  0.0,    -0.333, -0.667, -1.0,    -1.333,
                            -1.667, -2.0,   -2.333, -2.667, -3.0,   -3.333, -3.667,  -4.0,
                            -4.667, -5.333, -6.148, -7.254, -8.843, -11.31, -15.639, -25.0};
        c.columns = 1800;
        c.max_range = 200.0;
        c.range_at_10pct = 100.0;
        return true;
    }
    if (name == "vlp16") {
        // Velodyne VLP-16: 16 beams from +15 to -15 deg in 2 deg steps; 0.2 deg.
        for (int i = 0; i < 16; ++i) c.elevations_deg.push_back(15.0 - 2.0 * i);
        c.columns = 1800;
        c.max_range = 100.0;
        c.range_at_10pct = 50.0;
        return true;
    }
    if (name == "os1_64") {
        // Ouster OS1-64 (Rev 6/7): 64 beams spread evenly over +22.5 to -22.5 deg (0.714 deg),
        // in its default mode 1024x10 (1024 columns a turn at 10 Hz, 0.35 deg; 2048x10 is
        // `columns: 2048`); 0.3 m minimum range, 120 m maximum, a 10 % target detected half the
        // time at 60 m (the data sheet's order for Rev 6).
        // Like the Velodynes it turns clockwise and starts its frame at the rear (the connector
        // side, encoder angle 0), so per-point time follows the same rule.
        for (int i = 0; i < 64; ++i) c.elevations_deg.push_back(22.5 - 45.0 * i / 63.0);
        c.columns = 1024;
        c.min_range = 0.3;
        c.max_range = 120.0;
        c.range_at_10pct = 60.0;
        return true;
    }
    if (name == "livox_avia" || name == "solid_state") {
        // Livox Avia-like: 70.4 deg circular field, six tracks of a non-repetitive rosette,
        // 20k pulses a 0.1 s frame, 190 m for a 10 % target.
        c.model = "livox_avia";
        c.pattern = ScanPattern::kRosette;
        c.points_per_scan = 20000;
        c.fov_deg = 70.4;
        c.rosette_lasers = 6;
        c.max_range = 200.0;
        c.range_at_10pct = 190.0;
        return true;
    }
    return false;
}

std::string sensor_preset_names() {
    return "hdl64e, vlp32c, vlp16, os1_64, livox_avia (solid_state)";
}

SensorModel::SensorModel(const SensorConfig& config) : config_(config) {
    if (config_.pattern != ScanPattern::kSpinning) return;
    const int rings = static_cast<int>(config_.elevations_deg.size());
    const int cols = std::max(1, config_.columns);
    spinning_.reserve(static_cast<std::size_t>(rings) * cols);
    for (int r = 0; r < rings; ++r) {
        for (int c = 0; c < cols; ++c) {
            double az = 360.0 * c / cols;  // counter-clockwise from forward
            if (az > 180.0) az -= 360.0;
            const double t = period() * (180.0 - az) / 360.0;  // clockwise from the rear
            const double oz =
                r < static_cast<int>(config_.beam_origin_z.size()) ? config_.beam_origin_z[r] : 0.0;
            Pulse p{direction(az, config_.elevations_deg[r]),
                    float(az * kDeg),
                    float(std::min(t, period() * 0.999999)),
                    float(oz),
                    static_cast<std::uint16_t>(r),
                    false};
            p.blocked = into_ego_box(p.dir);
            spinning_.push_back(p);
        }
    }
}

int SensorModel::rings() const {
    return config_.pattern == ScanPattern::kSpinning
               ? static_cast<int>(config_.elevations_deg.size())
               : config_.rosette_lasers;
}

bool SensorModel::into_ego_box(const Eigen::Vector3f& dir) const {
    if (!config_.has_ego_box) return false;
    double t0 = 0.0, t1 = config_.max_range;
    for (int k = 0; k < 3; ++k) {
        const double lo = config_.ego_box.min()[k], hi = config_.ego_box.max()[k];
        if (std::abs(dir[k]) < 1e-12) {
            if (0.0 < lo || 0.0 > hi) return false;
            continue;
        }
        double a = lo / dir[k], b = hi / dir[k];
        if (a > b) std::swap(a, b);
        t0 = std::max(t0, a);
        t1 = std::min(t1, b);
    }
    return t0 <= t1;
}

const std::vector<Pulse>& SensorModel::pulses(std::size_t index,
                                              std::vector<Pulse>& scratch) const {
    if (config_.pattern == ScanPattern::kSpinning) return spinning_;
    // Two counter-rotating prisms deflect each laser along a rose curve; the phase runs on from
    // scan to scan, so the pattern does not repeat. The lasers sit in a short vertical line.
    const int n = std::max(1, config_.points_per_scan);
    const int lasers = std::max(1, config_.rosette_lasers);
    const double half_fov = 0.5 * config_.fov_deg;
    const double f1 = 127.3, f2 = -83.9;  // prism rates [Hz]
    scratch.resize(static_cast<std::size_t>(n));
    for (int k = 0; k < n; ++k) {
        const double t_in_scan = period() * k / n;
        const double tau = period() * static_cast<double>(index) + t_in_scan;
        const double a1 = 2 * M_PI * f1 * tau, a2 = 2 * M_PI * f2 * tau;
        const int laser = k % lasers;
        const double offset = (laser - 0.5 * (lasers - 1)) * 0.8;
        const double u = 0.5 * half_fov * (std::cos(a1) + std::cos(a2));
        const double v = 0.5 * half_fov * (std::sin(a1) + std::sin(a2)) + offset;
        Pulse& p = scratch[static_cast<std::size_t>(k)];
        p.dir = direction(u, v);
        p.azimuth = static_cast<float>(std::atan2(p.dir.y(), p.dir.x()));
        p.time = static_cast<float>(t_in_scan);
        p.origin_z = 0.0f;
        p.ring = static_cast<std::uint16_t>(laser);
        p.blocked = into_ego_box(p.dir);
    }
    return scratch;
}

double SensorModel::return_power(double reflectivity, double cos_incidence, double range) const {
    const double ratio = config_.range_at_10pct / std::max(range, 1e-3);
    return reflectivity * std::pow(std::max(cos_incidence, 0.02), 0.3) * ratio * ratio / 0.1;
}

double SensorModel::detection_probability(double power) {
    const double t = std::clamp((power - 0.6) / 0.8, 0.0, 1.0);
    return t * t * (3 - 2 * t);
}

double SensorModel::intensity(double reflectivity, double power) {
    return std::clamp(reflectivity * std::sqrt(std::clamp((power - 2.5) / 22.5, 0.0, 1.0)), 0.0,
                      1.0);
}

}  // namespace ltm::sim

namespace ltm::sim {

bool replace_sensor(const std::string& name, SensorConfig& config) {
    SensorConfig s;
    if (!make_sensor_preset(name, s)) return false;
    s.height = config.height;
    s.has_ego_box = config.has_ego_box;
    s.ego_box = config.ego_box;
    s.motion_distortion = config.motion_distortion;
    s.per_point_time = config.per_point_time;
    config = s;
    return true;
}

}  // namespace ltm::sim
