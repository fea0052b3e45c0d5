#pragma once
// Scan-to-local-map registration (METHOD.md Eq. 5, 8): Gauss-Newton over SE(3) on the IMLS
// residuals n_x.(R p + t - y), with a Geman-McClure kernel and the voxels' stability weights, then
// convergence, degeneracy and covariance.
//
// Perturbation: R <- Exp(dr) R, t <- t + dt, i.e. a rotation about the sensor position in the
// map (= odometry) axes. Hessian, covariance and degenerate directions use this order
// [dt (m); dr (rad)], which is also the pose covariance order of nav_msgs/Odometry.
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <functional>
#include <vector>

#include "registration/core/imls.hpp"
#include "registration/core/parallel.hpp"
#include "registration/core/registration_config.hpp"
#include "registration/core/se3.hpp"
#include "registration/core/voxel_grid.hpp"

namespace ltm::registration {

struct RegistrationResult {
    enum class Status { kConverged, kNotConverged, kTooFewCorrespondences, kNumericalFailure };
    Status status = Status::kTooFewCorrespondences;
    Eigen::Isometry3d T_map_lidar = Eigen::Isometry3d::Identity();
    int iterations = 0;
    std::size_t points = 0;                  // registration points given
    std::size_t correspondences = 0;         // points with an IMLS residual at the last iteration
    std::size_t inliers = 0;                 // ... with |residual| under config inlier_distance
    double residual_rms = 0.0;               // of the residuals of those points [m]
    double kernel_scale = 0.0;               // Geman-McClure scale at the last iteration [m]
    double last_step_translation = 0.0;      // [m]
    double last_step_rotation = 0.0;         // [rad]
    Matrix6d hessian = Matrix6d::Zero();     // sum w J^T J at the last iteration
    Matrix6d covariance = Matrix6d::Zero();  // sigma^2 H^-1 (degenerate directions capped)
    // Smallest eigenvalue of the normalised Hessian: the weighted mean of (J.v)^2 along the
    // weakest direction v (1/3 per axis when normals point every way).
    double min_information = 0.0;
    // Unit eigenvectors of the normalised Hessian with too little information, in
    // [dt (m); dr * degeneracy_length (m)] (rotation as displacement at the lever arm).
    std::vector<Vector6d> degenerate_directions;

    bool ok() const { return status == Status::kConverged || status == Status::kNotConverged; }
    // Inliers over the correspondences: how well the matched part of the scan fits (0..1).
    double inlier_fraction() const {
        return correspondences ? double(inliers) / double(correspondences) : 0.0;
    }
    // Correspondences over the points given: how much of the scan the map explains (0..1).
    double overlap() const { return points ? double(correspondences) / double(points) : 0.0; }
};

const char* to_string(RegistrationResult::Status status);

// Keeps scratch buffers between calls (no allocation once warm): one instance per thread.
class Registration {
  public:
    // `parallel` may be null (serial); it must outlive the Registration.
    Registration(const RegistrationConfig& config, double voxel_size,
                 ParallelFor* parallel = nullptr);

    // points: the scan in the LiDAR frame; guess: the initial T_map_lidar (the grid's frame).
    RegistrationResult align(const std::vector<Eigen::Vector3f>& points, const VoxelGrid& grid,
                             const Eigen::Isometry3d& guess);

    const RegistrationConfig& config() const { return config_; }
    ImlsParams imls_params() const { return imls_; }

    // The IMLS distance at x of points[i] of the last align() on `grid` (the same points and
    // grid: a check of the result), with the neighbours that align() found for that point's
    // voxel; a point now in another voxel (or an index beyond the last align's points) is looked
    // up in the grid. Equal to imls_distance(grid, x, imls_params(), result), without the 27
    // look-ups a point that stayed in its voxel.
    bool imls_after_align(std::size_t i, const VoxelGrid& grid, const Eigen::Vector3f& x,
                          ImlsResult* result);

  private:
    struct Accumulator {
        Matrix6d H = Matrix6d::Zero();
        Vector6d b = Vector6d::Zero();
        double weighted_sq = 0.0;  // sum w r^2
        double weight = 0.0;       // sum w
        double plain_sq = 0.0;     // sum r^2
        std::size_t count = 0;

        void add(const Accumulator& o) {
            H += o.H;
            b += o.b;
            weighted_sq += o.weighted_sq;
            weight += o.weight;
            plain_sq += o.plain_sq;
            count += o.count;
        }
    };

    struct Residual {
        Eigen::Matrix<float, 6, 1> J;  // d error / d [dt; dr]
        float error = 0.0f;            // IMLS distance [m]
        float weight = 0.0f;           // stability weight; 0: no correspondence
    };
    // The usable voxels around a point's voxel, valid while the point stays in that voxel.
    struct NeighbourCache {
        VoxelKey key = ~VoxelKey(0);  // no entry
        int count = 0;
        std::uint32_t index[27];
    };
    struct Spectrum {
        Vector6d d;     // scaling of [dt; dr]
        double weight;  // total weight
        Eigen::SelfAdjointEigenSolver<Matrix6d> eig;
    };
    // The IMLS distance at x with the usable neighbours of x's voxel, looked up only when x left
    // the voxel `c` holds them for.
    bool cached_imls(NeighbourCache& c, const VoxelGrid& grid, const Eigen::Vector3f& x,
                     ImlsResult* result) const;
    void for_chunks(std::size_t n,
                    const std::function<void(std::size_t, std::size_t, std::size_t)>& f);
    void linearise(const std::vector<Eigen::Vector3f>& points, const VoxelGrid& grid,
                   const Eigen::Isometry3d& T, Accumulator* total);
    Spectrum spectrum(const Accumulator& acc) const;
    void analyse(const Accumulator& acc, RegistrationResult* result) const;

    RegistrationConfig config_;
    ImlsParams imls_;
    ParallelFor* parallel_;
    std::vector<Residual> residuals_;
    std::vector<NeighbourCache> cache_;
    std::vector<float> abs_errors_;
    std::vector<Accumulator> partial_;
    double kernel_used_ = 0.0;
};

}  // namespace ltm::registration
