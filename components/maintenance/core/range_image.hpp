#pragma once
// The range image of one scan (a "view"): the nearest return in each direction, on an
// azimuth x elevation grid in the sensor frame. It answers what the scan says about a small cube:
// a beam returned at the cube (surface), a beam passed through it and returned beyond (free), every
// beam through it stopped before it (occluded), or no beam went through it (unseen: between the
// beams, outside the field of view, or no return). This is ray casting along the scan's own rays:
// the measured returns are the occluders, so parked cars, walls and the moving object itself
// occlude exactly as they did when the scan was taken.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "maintenance/core/maintenance_config.hpp"

namespace ltm::maintenance {

enum class Visibility : std::uint8_t { kUnseen, kOccluded, kSurface, kFree };

class RangeImage {
  public:
    RangeImage() = default;
    // Points in the sensor frame; non-finite points and returns outside [min_range, max_range]
    // are ignored. The elevation band is the scan's own (any sensor, any mounting).
    RangeImage(const RangeImageConfig& config, const std::vector<Eigen::Vector3f>& points);

    // The cube of edge `size` centred at `p` (sensor frame). A return counts as at the cube
    // when its range is within `margin` of the cube's centre's, as beyond it when farther.
    Visibility classify(const Eigen::Vector3f& p, float size, float margin) const;

    bool empty() const { return rows_ == 0; }
    int rows() const { return rows_; }
    int cols() const { return cols_; }
    std::size_t returns() const { return returns_; }
    std::size_t memory_bytes() const { return range_cm_.capacity() * sizeof(std::uint16_t); }

  private:
    // Range [m] of pixel (row, col), 0 when it has no return.
    float at(int row, int col) const {
        return 0.01f * float(range_cm_[std::size_t(row) * std::size_t(cols_) + std::size_t(col)]);
    }

    RangeImageConfig config_;
    float az_res_ = 0.0f, el_res_ = 0.0f;  // [rad]
    float el_min_ = 0.0f;                  // [rad] elevation of row 0's lower edge
    int rows_ = 0, cols_ = 0;
    std::size_t returns_ = 0;
    std::vector<std::uint16_t> range_cm_;  // nearest return [cm], 0: none
    std::vector<int> next_row_;            // the first row >= r with a return (rows_ if none)
};

}  // namespace ltm::maintenance
