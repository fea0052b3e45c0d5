#pragma once
// Which rotation predicts the next scan of a sparse stream better: the constant turn rate, or
// holding the last heading (issue 27, real Livox every 5th keyframe). A handheld sensor's
// keyframes 1-2.6 s apart swing left and right (+33, -38, -31, +50, -32 deg a step on hku-avia
// session 1): extrapolating the last turn doubles the error where holding the heading halves it
// (reference poses, every 5th keyframe: mean rotation error 33.9 deg extrapolated, 23.6 deg held;
// a car's corners every 10th scan: 5.9 and 6.9 deg). Scored on the scans that measured their
// rotation, as running means of both errors; the held heading is used only when its mean error is
// at most `ratio` times the extrapolation's, over at least kMinScans scans.
namespace ltm::odometry {

class HeadingSkill {
  public:
    static constexpr int kMinScans = 3;
    explicit HeadingSkill(double ratio) : ratio_(ratio) {}
    // A scan whose rotation was measured: the rotation errors [rad] of the constant turn rate's
    // prediction and of the last heading, against the fit.
    void observe(double extrapolated_error, double held_error);
    // Whether the next prediction should hold the last heading (ratio 0: never).
    bool hold() const;
    double extrapolated_error() const { return extrapolated_; }
    double held_error() const { return held_; }
    void reset() { scans_ = 0; }

  private:
    double ratio_;
    int scans_ = 0;
    double extrapolated_ = 0.0, held_ = 0.0;  // running means [rad]
};

}  // namespace ltm::odometry
