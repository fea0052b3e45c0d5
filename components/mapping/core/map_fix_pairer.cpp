#include "mapping/core/map_fix_pairer.hpp"

#include <cmath>

namespace ltm::mapping {

MapFixPairer::Key MapFixPairer::key(double stamp) { return std::llround(stamp * 1e9); }

std::optional<PairedFix> MapFixPairer::match(Key k) {
    const auto kf = keyframes_.find(k);
    const auto ok = usable_.find(k);
    const auto pose = poses_.find(k);
    if (kf == keyframes_.end() || ok == usable_.end() || pose == poses_.end()) return std::nullopt;
    std::optional<PairedFix> out;
    if (ok->second) out = PairedFix{kf->second, pose->second};
    keyframes_.erase(kf);
    usable_.erase(ok);
    poses_.erase(pose);
    return out;
}

std::optional<PairedFix> MapFixPairer::keyframe(double stamp, const FixKeyframe& keyframe) {
    if (!std::isfinite(stamp)) return std::nullopt;
    keyframes_[key(stamp)] = keyframe;
    bound(keyframes_);
    return match(key(stamp));
}

std::optional<PairedFix> MapFixPairer::state(double stamp, bool tracking) {
    if (!std::isfinite(stamp)) return std::nullopt;
    run_ = tracking ? run_ + 1 : 0;
    usable_[key(stamp)] = tracking && run_ >= min_run_;
    bound(usable_);
    return match(key(stamp));
}

std::optional<PairedFix> MapFixPairer::pose(double stamp, const Eigen::Isometry3d& T_world_lidar) {
    if (!std::isfinite(stamp) || !T_world_lidar.matrix().allFinite()) return std::nullopt;
    poses_[key(stamp)] = T_world_lidar;
    bound(poses_);
    return match(key(stamp));
}

}  // namespace ltm::mapping
