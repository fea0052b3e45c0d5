#include "self_check.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <cmath>
#include <fstream>
#include <limits>

#include "common/core/io_error.hpp"

namespace ltm::odometry::bench {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double path_length(const std::vector<Eigen::Vector3d>& p) {
    double s = 0.0;
    for (std::size_t i = 1; i < p.size(); ++i) s += (p[i] - p[i - 1]).norm();
    return s;
}

}  // namespace

SelfCheck self_check(const std::vector<FrameResult>& results, const common::PoseList& reference) {
    SelfCheck s;
    s.frames = results.size();
    std::vector<Eigen::Vector3d> est;
    for (const FrameResult& r : results) {
        s.degenerate += r.status == FrameStatus::kDegenerate;
        s.registered += r.registered();
        s.published += r.pose_valid();
        s.weak += r.pose_valid() && r.constrained_directions < 3 && r.information.trace() > 0.0;
        s.searched_along += r.profile_contrast > 0.0;
        s.moved_along += r.profile_shift != 0.0;
        s.spin_held += r.spin_hold;
        est.push_back(r.T_odom_lidar.translation());
    }
    s.path = path_length(est);
    s.step_error.assign(results.size(), kNaN);
    s.mahalanobis.assign(results.size(), kNaN);
    const std::size_t n = std::min(results.size(), reference.size());
    if (n == 0) return s;
    s.has_reference = true;
    std::vector<Eigen::Vector3d> ref;
    for (std::size_t i = 0; i < n; ++i) ref.push_back(reference[i].translation());
    est.resize(n);
    s.path = path_length(est);
    s.reference_path = path_length(ref);
    for (std::size_t i = 1; i < n; ++i) {
        const FrameResult& r = results[i];
        const Eigen::Isometry3d d_est = results[i - 1].T_odom_lidar.inverse() * r.T_odom_lidar;
        const Eigen::Isometry3d d_ref = reference[i - 1].inverse() * reference[i];
        // The step error in the odometry's axes (its rotation at the previous scan).
        const Eigen::Vector3d e =
            results[i - 1].T_odom_lidar.linear() * (d_est.translation() - d_ref.translation());
        s.step_error[i] = e.norm();
        if (r.registered() && e.norm() > 1.0) ++s.registered_off;
        if (!r.pose_valid() || r.status == FrameStatus::kRestarted) continue;
        const Eigen::Matrix3d C = r.covariance.topLeftCorner<3, 3>();
        if (!(C.trace() > 0.0)) continue;
        const double m = std::sqrt(std::max(0.0, e.dot(C.ldlt().solve(e))));
        s.mahalanobis[i] = m;
        ++s.steps;
        s.within_3_sigma += m <= 3.0;
    }
    return s;
}

void print_self_check(const SelfCheck& s, std::FILE* out) {
    const double f = s.frames ? 100.0 / double(s.frames) : 0.0;
    std::fprintf(out,
                 "observability: %zu of %zu scans degenerate (%.2f %%: position along a weak "
                 "direction from the motion model), %zu registered, %zu with a weak direction, "
                 "%zu searched along it (%zu moved by the search), %zu held by the spin hold\n",
                 s.degenerate, s.frames, f * double(s.degenerate), s.registered, s.weak,
                 s.searched_along, s.moved_along, s.spin_held);
    if (!s.has_reference) {
        std::fprintf(out, "path length: %.1f m (no reference)\n", s.path);
        return;
    }
    std::fprintf(out, "path length: %.1f m, reference %.1f m (%.2f %%)\n", s.path, s.reference_path,
                 s.reference_path > 0.0 ? 100.0 * s.path / s.reference_path : 0.0);
    std::fprintf(out,
                 "self-check: %zu scans registered while > 1 m off the reference step (%.2f %% of "
                 "scans); step errors within 3 sigma of the published covariance (position, "
                 "Mahalanobis): %zu of %zu (%.1f %%)\n",
                 s.registered_off, f * double(s.registered_off), s.within_3_sigma, s.steps,
                 s.steps ? 100.0 * double(s.within_3_sigma) / double(s.steps) : 0.0);
}

void write_frame_log(const std::string& path, const std::vector<FrameResult>& results,
                     const std::vector<double>& ms, const SelfCheck& s) {
    std::ofstream log(path);
    if (!log) throw common::IoError(path, "cannot write");
    log << "frame,status,ms,preprocess_ms,registration_ms,update_ms,input,registration_points,"
           "correspondences,attempts,iterations,coarse_iterations,residual_rms,degenerate,"
           "min_information,local_map,inlier_fraction,searched,segment,lost_for,"
           "search_used,constrained,info_t0,info_t1,info_t2,weak_x,weak_y,weak_z,"
           "profile_support,profile_contrast,profile_shift,sigma_weak,sigma_max,step_error,"
           "step_mahalanobis,heading_held,turn_rate,spin_held\n";
    for (std::size_t i = 0; i < results.size(); ++i) {
        const FrameResult& r = results[i];
        const Eigen::Matrix3d C = r.covariance.topLeftCorner<3, 3>();
        const Eigen::Vector3d& v = r.weak_direction;
        const double sigma_weak = std::sqrt(std::max(0.0, v.dot(C * v)));
        const double sigma_max = std::sqrt(
            std::max(0.0, Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(C, Eigen::EigenvaluesOnly)
                              .eigenvalues()[2]));
        log << i << ',' << to_string(r.status) << ',' << (i < ms.size() ? ms[i] : 0.0) << ','
            << r.preprocess_ms << ',' << r.registration_ms << ',' << r.update_ms << ','
            << r.input_points << ',' << r.registration_points << ',' << r.correspondences << ','
            << r.attempts << ',' << r.iterations << ',' << r.coarse_iterations << ','
            << r.residual_rms << ',' << r.degenerate_directions.size() << ',' << r.min_information
            << ',' << r.local_map_id << ',' << r.inlier_fraction << ',' << r.searched << ','
            << r.segment << ',' << r.lost_for << ',' << r.search_used << ','
            << r.constrained_directions << ',' << r.translation_information[0] << ','
            << r.translation_information[1] << ',' << r.translation_information[2] << ',' << v.x()
            << ',' << v.y() << ',' << v.z() << ',' << r.profile_support << ',' << r.profile_contrast
            << ',' << r.profile_shift << ',' << sigma_weak << ',' << sigma_max << ','
            << s.step_error[i] << ',' << s.mahalanobis[i] << ',' << r.heading_held << ','
            << r.turn_rate << ',' << (r.spin_hold ? r.spin_held : -1.0) << '\n';
    }
}

}  // namespace ltm::odometry::bench
