#pragma once
// The spin hold (issue 27): while the sensor turns fast, its position along a translation direction
// the registration did not observe stays where it was instead of going on with the velocity.
//
// Why: a narrow view turning on the spot (a handheld Livox, a robot spinning in place) constrains
// one translation direction of three in most scans. Along the others the position of a
// degenerate scan is the motion model's, and its velocity there is itself the extrapolation of
// earlier guesses (and, in a turn, the last step's translation turned with the turn rate): on the
// simulated handheld_spins every 2nd scan it carried 73.5 m of the 125 m summed step error while
// the true step was under 0.1 m. A fast turn is evidence of no travel: a platform spinning at
// tens of degrees a second goes nowhere fast (a handheld sensor spins on the spot; a car turning
// at speed turns at 10-30 deg/s). So where nothing measured the translation, no translation.
#include <Eigen/Geometry>
#include <vector>

#include "registration/core/se3.hpp"

namespace ltm::odometry {

// The recent rotation rate: the rates of the published steps smoothed over `window` seconds
// (exponentially, by sensor time). A fit's own rotation is noisy where its translation is
// unobserved (in a spin the fits of one Livox sweep measured 5-360 deg/s where the truth was
// 100): the criterion is the larger of the fit's rate and this.
class RecentTurnRate {
  public:
    void add(double rate, double dt, double window);
    double rate() const { return rate_; }
    void reset() { rate_ = 0.0; }

  private:
    double rate_ = 0.0;  // [deg/s]
};

// The rotation rate [deg/s] from `from` to `to` over `dt` seconds (0 when dt is not positive).
double turn_rate(const Eigen::Isometry3d& from, const Eigen::Isometry3d& to, double dt);

// The position of `pose` along `directions` (unit or not, odometry axes; their span) moved to
// `anchor`'s; the rest of the position and the rotation untouched. Returns how far it moved [m].
double hold_along(const Eigen::Vector3d& anchor, const std::vector<Eigen::Vector3d>& directions,
                  Eigen::Isometry3d* pose);

// Whether a registration's degenerate directions ([dt; dr * lever], unit, odometry axes) hold a
// rotation about `axis` (unit, odometry axes): the projection of the pure rotation [0; axis] onto
// their span is more than 0.7 of it. Then the fit could not measure a turn about that axis (the
// ground alone cannot see a turn about the vertical).
bool turn_unobserved(const std::vector<registration::Vector6d>& directions,
                     const Eigen::Vector3d& axis);

// The translation parts of a registration's degenerate directions ([dt; dr * lever], unit) that
// are mostly a translation (|dt| > 0.7).
std::vector<Eigen::Vector3d> translation_parts(
    const std::vector<registration::Vector6d>& directions);

}  // namespace ltm::odometry
