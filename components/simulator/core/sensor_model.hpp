#pragma once
// LiDAR sensor models: beam layouts (spinning multi-beam and a non-repetitive rosette like the
// Livox Avia), timing, range limits, return detection, range noise and intensity.
#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <vector>

namespace ltm::sim {

enum class ScanPattern { kSpinning, kRosette };

struct SensorConfig {
    std::string model = "vlp32c";  // preset the values came from
    ScanPattern pattern = ScanPattern::kSpinning;
    std::vector<double> elevations_deg;  // spinning: one per ring, top ring first [deg]
    int columns = 1800;                  // spinning: firings per revolution
    std::vector<double> beam_origin_z;   // spinning: height of each beam's origin [m] (empty: 0)
    int points_per_scan = 20000;         // rosette: pulses a scan
    double fov_deg = 70.4;               // rosette: full cone angle [deg]
    int rosette_lasers = 6;              // rosette: parallel tracks
    double rate_hz = 10.0;               // scans a second
    double min_range = 1.0;              // [m] nearer returns are discarded
    double max_range = 120.0;            // [m]
    double range_at_10pct = 60.0;    // [m] where a 10 % target at normal incidence is at threshold
    double range_noise = 0.02;       // [m] 1-sigma, Gaussian along the beam
    double dropout = 0.002;          // probability that a return is lost at random
    double intensity_noise = 0.1;    // relative 1-sigma of the intensity (plus 0.02 absolute)
    bool per_point_time = true;      // fill PointCloud::time (s after the stamp) of distorted scans
    bool motion_distortion = false;  // each pulse from the pose at its firing time
    double height = 1.0;             // [m] sensor above the ground (waypoint routes)
    bool has_ego_box = false;        // pulses into this sensor-frame box are lost (own vehicle)
    Eigen::AlignedBox3d ego_box;
};

// Fills `config` with a preset: hdl64e, vlp32c, vlp16, os1_64, livox_avia (alias solid_state).
// False when the name is unknown.
bool make_sensor_preset(const std::string& name, SensorConfig& config);
std::string sensor_preset_names();  // "hdl64e, vlp32c, ..." for messages
// Swaps the sensor for preset `name`, keeping how it is mounted and timed (height, ego box,
// motion distortion, per-point time). False for an unknown name (config unchanged).
bool replace_sensor(const std::string& name, SensorConfig& config);

struct Pulse {
    Eigen::Vector3f dir;  // unit, sensor frame (x forward, y left, z up)
    float azimuth;        // [rad] atan2(dir.y, dir.x)
    float time;           // [s] after the scan stamp
    float origin_z;       // [m] the pulse leaves from (0, 0, origin_z) in the sensor frame
    std::uint16_t ring;   // beam index (spinning: 0 = top), laser index (rosette)
    bool blocked;         // into the ego box
};

class SensorModel {
  public:
    explicit SensorModel(const SensorConfig& config);

    const SensorConfig& config() const { return config_; }
    double period() const { return 1.0 / config_.rate_hz; }
    int rings() const;
    // Pulses of scan `index` in output order. Spinning: ring by ring from the top, each ring
    // starting forward and turning counter-clockwise (the order of KITTI's files), while the
    // head spins clockwise from the rear (time 0 at azimuth 180 deg, as KISS-ICP assumes for
    // KITTI). Rosette: in firing order; the pattern never repeats from scan to scan.
    const std::vector<Pulse>& pulses(std::size_t index, std::vector<Pulse>& scratch) const;

    // Received power relative to the detection threshold: 1 for a 10 % Lambertian target at
    // normal incidence at range_at_10pct. Grazing returns fade more slowly than a cosine law.
    double return_power(double reflectivity, double cos_incidence, double range) const;
    // Probability that a return of this power is detected (soft threshold around 1).
    static double detection_probability(double power);
    // Intensity in [0, 1] before noise: the surface's reflectivity once the return is well
    // above the threshold, fading to 0 near it (as KITTI's far and grazing returns do).
    static double intensity(double reflectivity, double power);

  private:
    bool into_ego_box(const Eigen::Vector3f& dir) const;

    SensorConfig config_;
    std::vector<Pulse> spinning_;  // fixed pattern of spinning sensors
};

}  // namespace ltm::sim
