#include "registration/core/preprocess.hpp"

#include <algorithm>
#include <cmath>

namespace ltm::registration {
namespace {

constexpr int kDeskewBins = 256;  // exact poses at bin edges, linear blend in between

bool cell_key(const Eigen::Vector3f& p, float inv_cell, VoxelKey* key) {
    Eigen::Vector3i v;
    if (!voxel_coords(p, inv_cell, &v)) return false;
    *key = pack_key(v.x(), v.y(), v.z());
    return true;
}

}  // namespace

void VoxelDownsampler::sample(const std::vector<Eigen::Vector3f>& in, double cell,
                              std::size_t max_points, std::vector<Eigen::Vector3f>* out) {
    if (cell > 0.0) {
        run(in, cell, out);
    } else {
        out->clear();
        for (const Eigen::Vector3f& p : in) {
            if (p.allFinite()) out->push_back(p);
        }
    }
    if (out->size() <= max_points) return;
    const double step = double(out->size()) / double(max_points);
    for (std::size_t i = 0; i < max_points; ++i) (*out)[i] = (*out)[std::size_t(double(i) * step)];
    out->resize(max_points);
}

void VoxelDownsampler::run(const std::vector<Eigen::Vector3f>& in, double cell,
                           std::vector<Eigen::Vector3f>* out) {
    out->clear();
    cells_.reserve(in.size() / 4 + 16);
    cells_.clear();
    const float inv = float(1.0 / cell);
    VoxelKey last = ~VoxelKey(0);  // consecutive points often share a cell: it is taken
    for (const Eigen::Vector3f& p : in) {
        VoxelKey key;
        if (!cell_key(p, inv, &key) || key == last) continue;
        last = key;
        if (cells_.insert(key, 0).second) out->push_back(p);
    }
}

Preprocessor::Preprocessor(const PreprocessConfig& config, double voxel_size)
    : config_(config),
      map_cell_(config.map_sample_fraction * voxel_size),
      registration_cell_(config.registration_sample_fraction * voxel_size) {}

void Preprocessor::run(const common::PointCloud& cloud, const Vector6d* velocity,
                       PreprocessedScan* out) {
    const bool with_time = cloud.has_time() && cloud.time.size() == cloud.points.size();
    out->input_points = cloud.size();
    out->dropped_non_finite = 0;
    out->dropped_range = 0;
    out->deskewed = false;
    out->T_stamp_mid.setIdentity();
    // Crop, and the map-grid cell of each point kept (its index in the cloud with it). A point in
    // the cell of the point kept before it is never the first of its cell: it is left out here,
    // without a look-up (a scan stored ring by ring has runs of such points).
    kept_.clear();
    keys_.clear();
    const float min2 = float(config_.min_range * config_.min_range);
    const float max2 = float(config_.max_range * config_.max_range);
    const float inv = float(1.0 / map_cell_);
    VoxelKey last = ~VoxelKey(0);
    std::size_t cropped = 0;
    for (std::size_t i = 0; i < cloud.points.size(); ++i) {
        const Eigen::Vector3f& p = cloud.points[i];
        if (!p.allFinite() || (with_time && !std::isfinite(cloud.time[i]))) {
            ++out->dropped_non_finite;
            continue;
        }
        const float r2 = p.squaredNorm();
        if (r2 < min2 || r2 > max2) {
            ++out->dropped_range;
            continue;
        }
        ++cropped;
        VoxelKey key;
        if (!cell_key(p, inv, &key) || key == last) continue;
        last = key;
        kept_.push_back(std::uint32_t(i));
        keys_.push_back(key);
    }

    // Map grid: the first point of each cell.
    out->map_points.clear();
    map_times_.clear();
    cells_.reserve(cropped / 4 + 16);
    cells_.clear();
    constexpr std::size_t kAhead = 8;  // prefetch distance: hides the hash's cache misses
    for (std::size_t k = 0; k < kept_.size(); ++k) {
        if (k + kAhead < kept_.size()) cells_.prefetch(keys_[k + kAhead]);
        if (!cells_.insert(keys_[k], 0).second) continue;
        out->map_points.push_back(cloud.points[kept_[k]]);
        if (with_time) map_times_.push_back(cloud.time[kept_[k]]);
    }
    raw_map_points_.clear();
    mid_time_ = 0.0;
    if (with_time && config_.deskew && !map_times_.empty()) {
        if (!map_points_only_) raw_map_points_ = out->map_points;
        const auto [lo, hi] = std::minmax_element(map_times_.begin(), map_times_.end());
        mid_time_ = 0.5 * (double(*lo) + double(*hi));
    }
    if (with_time && config_.deskew && velocity != nullptr && velocity->allFinite()) {
        deskew(map_times_, *velocity, &out->map_points);
        out->T_stamp_mid = se3_exp(mid_time_ * *velocity);
        out->deskewed = true;
    }

    if (map_points_only_) {
        out->registration_points.clear();
        return;
    }
    registration_sampler_.run(out->map_points, registration_cell_, &out->registration_points);
    const std::size_t cap = std::size_t(config_.max_registration_points);
    auto& reg = out->registration_points;
    if (cap > 0 && reg.size() > cap) {
        // Even stride over the (spatially ordered) points keeps the coverage uniform.
        const double stride = double(reg.size()) / double(cap);
        for (std::size_t k = 0; k < cap; ++k) reg[k] = reg[std::size_t(k * stride)];
        reg.resize(cap);
    }
}

void Preprocessor::redeskew_map_points(const Vector6d& velocity, PreprocessedScan* out) {
    if (raw_map_points_.empty() || raw_map_points_.size() != out->map_points.size() ||
        !velocity.allFinite()) {
        return;
    }
    out->map_points = raw_map_points_;
    deskew(map_times_, velocity, &out->map_points);
    out->T_stamp_mid = se3_exp(mid_time_ * velocity);
    out->deskewed = true;
}

void Preprocessor::deskew(const std::vector<float>& times, const Vector6d& velocity,
                          std::vector<Eigen::Vector3f>* points) {
    if (times.empty()) return;
    const auto [lo, hi] = std::minmax_element(times.begin(), times.end());
    const double t0 = *lo, span = std::max(double(*hi) - t0, 1e-9);
    const double bin = span / kDeskewBins;
    // Pose of the sensor at time t relative to the stamp: Exp(t * velocity).
    std::vector<Eigen::Matrix3f> R(kDeskewBins + 1);
    std::vector<Eigen::Vector3f> t(kDeskewBins + 1);
    for (int k = 0; k <= kDeskewBins; ++k) {
        const Eigen::Isometry3d T = se3_exp((t0 + k * bin) * velocity);
        R[k] = T.linear().cast<float>();
        t[k] = T.translation().cast<float>();
    }
    for (std::size_t i = 0; i < points->size(); ++i) {
        const double f = (times[i] - t0) / bin;
        const int k = std::clamp(int(f), 0, kDeskewBins - 1);
        const float a = float(f - k);
        const Eigen::Vector3f& p = (*points)[i];
        (*points)[i] = (1.0f - a) * (R[k] * p + t[k]) + a * (R[k + 1] * p + t[k + 1]);
    }
}

}  // namespace ltm::registration
