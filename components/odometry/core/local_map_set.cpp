#include "odometry/core/local_map_set.hpp"

namespace ltm::odometry {

LocalMapSet::LocalMapSet(const OdometryConfig& config) : config_(config) {}

bool LocalMapSet::left_switch_box(const Eigen::Isometry3d& T_odom_lidar) const {
    const Eigen::Vector3d d = T_odom_lidar.translation() - current().T_odom_anchor().translation();
    return d.cwiseAbs().maxCoeff() > config_.local_map.switch_distance;
}

bool LocalMapSet::integrate(const std::vector<Eigen::Vector3f>& points,
                            const Eigen::Isometry3d& T_odom_lidar, double stamp) {
    bool started = false;
    if (active_.empty() || left_switch_box(T_odom_lidar)) {
        LocalMap map(next_id_++, T_odom_lidar, config_.voxel_size, config_.local_map.half_extent,
                     config_.voxel, stamp, config_.coarse_voxel_factor);
        map.set_segment(segment_);
        if (!active_.empty()) map.seed_from(active_.back());
        active_.push_back(std::move(map));
        started = true;
        while (active_.size() > std::size_t(config_.local_map.max_active_maps)) {
            finished_.push_back(std::move(active_.front()));
            active_.pop_front();
        }
    }
    const Eigen::Matrix3f R = T_odom_lidar.linear().cast<float>();
    for (LocalMap& map : active_) {
        const Eigen::Vector3f t = (T_odom_lidar.translation() - map.origin()).cast<float>();
        scratch_.resize(points.size());
        for (std::size_t i = 0; i < points.size(); ++i) scratch_[i] = R * points[i] + t;
        map.integrate(scratch_, t, stamp);
    }
    return started;
}

void LocalMapSet::finish_all() {
    for (LocalMap& map : active_) finished_.push_back(std::move(map));
    active_.clear();
}

void LocalMapSet::start_new_segment() {
    finish_all();
    ++segment_;
}

std::vector<LocalMap> LocalMapSet::take_finished() {
    std::vector<LocalMap> out;
    out.swap(finished_);
    return out;
}

std::size_t LocalMapSet::memory_bytes() const {
    std::size_t n = scratch_.capacity() * sizeof(Eigen::Vector3f);
    for (const LocalMap& m : active_) n += m.memory_bytes();
    for (const LocalMap& m : finished_) n += m.memory_bytes();
    return n;
}

}  // namespace ltm::odometry
