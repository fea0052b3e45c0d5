#pragma once
// Scan pre-processing (Algorithm 1, before registration): drop non-finite points, range crop,
// voxel down-sampling (a fine grid for the map update, a coarser one for registration), and
// de-skew when the scan has per-point times. Buffers are reused: no allocation once warm.
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "common/core/point_cloud.hpp"
#include "registration/core/registration_config.hpp"
#include "registration/core/se3.hpp"
#include "registration/core/voxel_hash.hpp"

namespace ltm::registration {

struct PreprocessedScan {
    std::vector<Eigen::Vector3f> map_points;           // LiDAR frame at the scan stamp
    std::vector<Eigen::Vector3f> registration_points;  // LiDAR frame at the scan stamp
    std::size_t input_points = 0;
    std::size_t dropped_non_finite = 0;
    std::size_t dropped_range = 0;
    bool deskewed = false;
    // The LiDAR at the middle of the sweep in the frame at the stamp, as de-skewing assumed it:
    // Exp(t_mid * velocity) (identity when not de-skewed). Points de-skewed with a wrong velocity
    // are off by (t - t_stamp) * error, on average half a sweep's worth: a registration of them
    // fixes the pose at the middle of the sweep, where that error averages out, and the pose at
    // the stamp follows only through this transform.
    Eigen::Isometry3d T_stamp_mid = Eigen::Isometry3d::Identity();
};

// Keeps the first point of each occupied cell of a grid of edge `cell` [m].
class VoxelDownsampler {
  public:
    void run(const std::vector<Eigen::Vector3f>& in, double cell,
             std::vector<Eigen::Vector3f>* out);
    // run() (cell > 0) or only the finite points (cell 0), then at most max_points of them taken
    // evenly through the result (the points a verification or a tracking step registers).
    void sample(const std::vector<Eigen::Vector3f>& in, double cell, std::size_t max_points,
                std::vector<Eigen::Vector3f>* out);

  private:
    VoxelHash cells_;
};

class Preprocessor {
  public:
    Preprocessor(const PreprocessConfig& config, double voxel_size);

    // velocity: the body-frame twist per second [v; w] used to de-skew (null: no de-skew).
    // De-skew happens only when the cloud has per-point times and the config asks for it.
    void run(const common::PointCloud& cloud, const Vector6d* velocity, PreprocessedScan* out);
    // De-skews the map points of the last run() again, from the raw points, with another velocity
    // (the motion estimated by registration, better than the prediction), and sets T_stamp_mid
    // for it. No-op without times.
    void redeskew_map_points(const Vector6d& velocity, PreprocessedScan* out);
    // Only the map points (a user that registers its own sample of them, as the localisation's
    // tracking): run() leaves registration_points empty and keeps no raw copy for
    // redeskew_map_points.
    void set_map_points_only(bool on) { map_points_only_ = on; }

  private:
    void deskew(const std::vector<float>& kept_times, const Vector6d& velocity,
                std::vector<Eigen::Vector3f>* points);

    PreprocessConfig config_;
    double map_cell_, registration_cell_;
    std::vector<float> map_times_;
    std::vector<std::uint32_t> kept_;  // cloud index of each point left for the map grid
    std::vector<Eigen::Vector3f> raw_map_points_;  // map points before de-skewing
    double mid_time_ = 0.0;                        // middle of the map points' times [s]
    std::vector<VoxelKey> keys_;                   // map-grid key of each of them
    VoxelHash cells_;
    VoxelDownsampler registration_sampler_;
    bool map_points_only_ = false;
};

}  // namespace ltm::registration
