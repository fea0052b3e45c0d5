#pragma once
// The range image of one scan (a "view"): the nearest return in each direction, on an
// azimuth x elevation grid in the sensor frame. It answers what the scan says about a small cube:
// a beam returned at the cube (surface), a beam passed through it and returned beyond (free), every
// beam through it stopped before it (occluded), or no beam went through it (unseen: between the
// beams, outside the field of view, or no return). A beam with no return that points above the
// horizon went to the sky: a cube it passes through is free (within RangeImageConfig::sky_range,
// and when no return near the cube ends before it); below the horizon a missing return stays
// unseen (a dark surface absorbed it). This is ray casting along the scan's own rays:
// the measured returns are the occluders, so parked cars, walls and the moving object itself
// occlude exactly as they did when the scan was taken.
#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <vector>

#include "maintenance/core/maintenance_config.hpp"

namespace ltm::maintenance {

enum class Visibility : std::uint8_t { kUnseen, kOccluded, kSurface, kFree };

class RangeImage {
  public:
    RangeImage() = default;
    // Points in the sensor frame; non-finite points and returns outside [min_range, max_range]
    // are ignored. The elevation band is the scan's own (any sensor, any mounting). `up`: the
    // world's vertical in the sensor frame (R_world_sensor^T z), the horizon of the sky rule.
    RangeImage(const RangeImageConfig& config, const std::vector<Eigen::Vector3f>& points,
               const Eigen::Vector3f& up = Eigen::Vector3f::UnitZ());

    // The cube of edge `size` centred at `p` (sensor frame). A return counts as at the cube
    // when its range is within `margin` of the cube's centre's, as beyond it (the cube seen
    // through) when farther. With `hit_margin` (>= 0, below `margin`) a return farther than the
    // cube's centre by more than `hit_margin` but not by `margin` is neither: another surface
    // just behind the cube, not the cube (a van's side 0.7 m in front of its neighbour's at 33 m
    // was "hit" by the neighbour's returns); the cube is then unseen unless another sample
    // returned at it (a return before it within `margin` stays at it, as without).
    // hit_margin < 0 (the default): `margin` both ways. `behind` (optional): the nearest such
    // return (sensor frame, at its pixel's centre direction) when the cube is unseen for it, so
    // that the caller can tell the cube's own surface at a grazing angle from another surface.
    Visibility classify(const Eigen::Vector3f& p, float size, float margin,
                        float hit_margin = -1.0f, Eigen::Vector3f* behind = nullptr) const;
    // Half the angular diagonal of a pixel [rad]: a return placed at its pixel's centre direction
    // is at most this times its range off.
    float pixel_half_diagonal() const { return 0.5f * std::hypot(az_res_, el_res_); }

    bool empty() const { return rows_ == 0; }
    int rows() const { return rows_; }
    int cols() const { return cols_; }
    std::size_t returns() const { return returns_; }
    std::size_t sky_pixels() const { return sky_pixels_; }  // beams without a return, up
    std::size_t memory_bytes() const { return range_cm_.capacity() * sizeof(std::uint16_t); }

  private:
    // A pixel's cell: 0 no return; 1..kMaxReturnCm the nearest return [cm]; kSky no return, the
    // beam above the horizon.
    static constexpr std::uint16_t kMaxReturnCm = 65000;  // 650 m
    static constexpr std::uint16_t kSky = 65535;

    std::uint16_t cell(int row, int col) const {
        return range_cm_[std::size_t(row) * std::size_t(cols_) + std::size_t(col)];
    }
    // Range [m] of pixel (row, col), 0 when it has no return.
    float at(int row, int col) const {
        const std::uint16_t c = cell(row, col);
        return c <= kMaxReturnCm ? 0.01f * float(c) : 0.0f;
    }
    // No return nearer than `r` [m] within `reach` [m] (across, at range r) of the direction
    // (az, el) [rad].
    bool clear_around(float az, float el, float r, float reach) const;
    // Marks the pixels without a return that look at the sky (the constructor's last step).
    void mark_sky(const Eigen::Vector3f& up);

    RangeImageConfig config_;
    float az_res_ = 0.0f, el_res_ = 0.0f;  // [rad]
    float el_min_ = 0.0f;                  // [rad] elevation of row 0's lower edge
    int rows_ = 0, cols_ = 0;
    std::size_t returns_ = 0, sky_pixels_ = 0;
    std::vector<std::uint16_t> range_cm_;  // per pixel: see cell()
    std::vector<int> next_row_;            // the first row >= r with a return (rows_ if none)
};

}  // namespace ltm::maintenance
