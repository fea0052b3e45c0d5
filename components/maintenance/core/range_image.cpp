#include "maintenance/core/range_image.hpp"

#include <algorithm>
#include <cmath>

namespace ltm::maintenance {

namespace {
constexpr float kPi = 3.14159265358979f;
constexpr float kDeg = kPi / 180.0f;
}  // namespace

RangeImage::RangeImage(const RangeImageConfig& config, const std::vector<Eigen::Vector3f>& points,
                       const Eigen::Vector3f& up)
    : config_(config) {
    az_res_ = float(config.azimuth_resolution) * kDeg;
    el_res_ = float(config.elevation_resolution) * kDeg;
    const float rmin = float(config.min_range), rmax = float(std::min(config.max_range, 650.0));
    float el_lo = kPi, el_hi = -kPi;
    std::vector<Eigen::Vector3f> polar;  // azimuth, elevation, range
    polar.reserve(points.size());
    for (const Eigen::Vector3f& p : points) {
        if (!p.allFinite()) continue;
        const float r = p.norm();
        if (!(r >= rmin && r <= rmax) || r <= 0.0f) continue;
        const float el = std::asin(std::clamp(p.z() / r, -1.0f, 1.0f));
        polar.emplace_back(std::atan2(p.y(), p.x()), el, r);
        el_lo = std::min(el_lo, el);
        el_hi = std::max(el_hi, el);
    }
    if (polar.empty()) return;
    el_min_ = el_lo - 0.5f * el_res_;
    rows_ = int(std::floor((el_hi - el_min_) / el_res_)) + 1;
    cols_ = std::max(1, int(std::ceil(2.0f * kPi / az_res_)));
    range_cm_.assign(std::size_t(rows_) * std::size_t(cols_), 0);
    for (const Eigen::Vector3f& q : polar) {
        int col = int(std::floor((q.x() + kPi) / az_res_));
        col = ((col % cols_) + cols_) % cols_;
        const int row = std::clamp(int(std::floor((q.y() - el_min_) / el_res_)), 0, rows_ - 1);
        std::uint16_t& cell = range_cm_[std::size_t(row) * std::size_t(cols_) + std::size_t(col)];
        const auto cm = std::uint16_t(std::clamp(q.z() * 100.0f + 0.5f, 1.0f, float(kMaxReturnCm)));
        if (cell == 0 || cm < cell) cell = cm;
        ++returns_;
    }
    // Rows between the beams stay empty: the footprint of a cube is sampled on the beams' rows.
    next_row_.assign(std::size_t(rows_) + 1, rows_);
    for (int row = rows_ - 1; row >= 0; --row) {
        bool any = false;
        for (int c = 0; c < cols_ && !any; ++c) any = at(row, c) > 0.0f;
        next_row_[std::size_t(row)] = any ? row : next_row_[std::size_t(row) + 1];
    }
    mark_sky(up);
}

void RangeImage::mark_sky(const Eigen::Vector3f& up_in) {
    if (!(config_.sky_range > 0.0) || !up_in.allFinite() || !(up_in.norm() > 1e-6f)) return;
    const Eigen::Vector3f up = up_in.normalized();
    const float up_xy = up.head<2>().norm();
    const float min_dot = std::sin(float(config_.sky_elevation) * kDeg);
    const auto n_cols = std::size_t(cols_);
    std::vector<float> col_cos(n_cols), col_sin(n_cols);
    for (int c = 0; c < cols_; ++c) {
        const float az = (float(c) + 0.5f) * az_res_ - kPi;
        col_cos[std::size_t(c)] = std::cos(az);
        col_sin[std::size_t(c)] = std::sin(az);
    }
    // Only the beams' rows (rows with a return): a row between the beams is never sampled.
    for (int row = next_row_[0]; row < rows_; row = next_row_[std::size_t(row) + 1]) {
        const float el = el_min_ + (float(row) + 0.5f) * el_res_;
        const float s = std::sin(el), co = std::cos(el);
        if (s * up.z() + co * up_xy < min_dot) continue;  // no pixel of this beam is sky
        for (std::size_t col = 0; col < n_cols; ++col) {
            std::uint16_t& v = range_cm_[std::size_t(row) * n_cols + col];
            if (v != 0) continue;
            if (s * up.z() + co * (col_cos[col] * up.x() + col_sin[col] * up.y()) < min_dot)
                continue;
            v = kSky;
            ++sky_pixels_;
        }
    }
}

bool RangeImage::clear_around(float az, float el, float r, float reach) const {
    const float half = std::atan2(reach, r);
    const float half_az = std::min(half / std::max(std::cos(el), 0.05f), kPi);
    const int r0 = std::max(0, int(std::floor((el - half - el_min_) / el_res_)));
    const int r1 = std::min(rows_ - 1, int(std::floor((el + half - el_min_) / el_res_)));
    const int c0 = int(std::floor((az - half_az + kPi) / az_res_));
    const int c1 = std::min(c0 + cols_ - 1, int(std::floor((az + half_az + kPi) / az_res_)));
    const auto before_cm = std::uint16_t(std::clamp(r * 100.0f, 0.0f, float(kMaxReturnCm)));
    for (int row = r0 > r1 ? rows_ : next_row_[std::size_t(r0)]; row <= r1;
         row = next_row_[std::size_t(row) + 1]) {
        for (int c = c0; c <= c1; ++c) {
            const std::uint16_t v = cell(row, ((c % cols_) + cols_) % cols_);
            if (v != 0 && v <= before_cm) return false;
        }
    }
    return true;
}

Visibility RangeImage::classify(const Eigen::Vector3f& p, float size, float margin,
                                float hit_margin, Eigen::Vector3f* behind_return) const {
    if (rows_ == 0 || !p.allFinite()) return Visibility::kUnseen;
    const float at = hit_margin >= 0.0f ? std::min(hit_margin, margin) : margin;
    const float r = p.norm();
    if (r <= 0.5f * size) return Visibility::kUnseen;
    const float az = std::atan2(p.y(), p.x());
    const float el = std::asin(std::clamp(p.z() / r, -1.0f, 1.0f));
    // The cube's angular half-extent (its inscribed sphere: a beam this close passes through it).
    const float half = std::atan2(0.5f * size, r);
    const float cos_el = std::max(std::cos(el), 0.05f);
    const float half_az = std::min(half / cos_el, kPi);
    const int r0 = int(std::floor((el - half - el_min_) / el_res_));
    const int r1 = int(std::floor((el + half - el_min_) / el_res_));
    if (r1 < 0 || r0 >= rows_) return Visibility::kUnseen;
    const int c0 = int(std::floor((az - half_az + kPi) / az_res_));
    const int c1 = int(std::floor((az + half_az + kPi) / az_res_));
    const int max_samples = std::max(1, config_.max_samples);
    // The rows with returns in the footprint, max_samples of them evenly.
    int rows[64];
    int n_rows = 0;
    for (int row = next_row_[std::size_t(std::max(r0, 0))]; row <= std::min(r1, rows_ - 1);
         row = next_row_[std::size_t(row) + 1]) {
        if (n_rows < 64) rows[n_rows++] = row;
    }
    if (n_rows == 0) return Visibility::kUnseen;
    const int row_step = std::max(1, (n_rows + max_samples - 1) / max_samples);
    const int col_step = std::max(1, (c1 - c0 + max_samples - 1) / max_samples);
    int beyond = 0, before = 0, behind = 0, sky = 0;
    float behind_range = 0.0f;
    int behind_row = 0, behind_col = 0;
    for (int k = 0; k < n_rows; k += row_step) {
        const int row = rows[k];
        for (int c = c0; c <= c1; c += col_step) {
            const std::uint16_t v = cell(row, ((c % cols_) + cols_) % cols_);
            if (v == 0) continue;
            if (v == kSky) {
                ++sky;
                continue;
            }
            const float range = 0.01f * float(v);
            if (range > r + margin) {
                ++beyond;
            } else if (range < r - margin) {
                ++before;
            } else if (range <= r + at) {
                return Visibility::kSurface;  // a surface return wins over every other sample
            } else {  // just behind the cube: neither at it nor (surely) through it
                if (behind++ == 0 || range < behind_range) {
                    behind_range = range;
                    behind_row = row;
                    behind_col = ((c % cols_) + cols_) % cols_;
                }
            }
        }
    }
    // A return just behind the cube says neither: never seen through on its strength either.
    if (behind > 0) {
        if (behind_return) {
            const float a = (float(behind_col) + 0.5f) * az_res_ - kPi;
            const float e = el_min_ + (float(behind_row) + 0.5f) * el_res_;
            *behind_return = behind_range * Eigen::Vector3f(std::cos(e) * std::cos(a),
                                                            std::cos(e) * std::sin(a), std::sin(e));
        }
        return Visibility::kUnseen;
    }
    if (beyond > 0) return Visibility::kFree;
    if (before > 0) return Visibility::kOccluded;
    // Only beams to the sky through the cube: free when it is within their range and nothing
    // around it returned before its far side (the object's own edge, a lost return on a surface).
    if (sky > 0 && r + margin < float(config_.sky_range) &&
        clear_around(az, el, r + margin, 0.5f * size + float(config_.sky_clearance)))
        return Visibility::kFree;
    return Visibility::kUnseen;
}

}  // namespace ltm::maintenance
