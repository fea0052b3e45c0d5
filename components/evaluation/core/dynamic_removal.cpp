#include "evaluation/core/dynamic_removal.hpp"

#include <cmath>

#include "evaluation/core/point_grid.hpp"

namespace ltm::eval {

bool append_labelled_scan(const common::PointCloud& cloud, const std::vector<std::uint32_t>& labels,
                          const Eigen::Isometry3d& T_world_sensor, common::LabelScheme scheme,
                          bool changed_is_dynamic, double max_range, LabelledMap& map) {
    if (labels.size() != cloud.size()) return false;
    const Eigen::Isometry3f T = T_world_sensor.cast<float>();
    const double max_r2 = max_range * max_range;
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const Eigen::Vector3f& p = cloud.points[i];
        if (!p.allFinite()) continue;
        if (max_range > 0.0 && p.cast<double>().squaredNorm() > max_r2) continue;
        map.points.push_back(T * p);
        map.dynamic.push_back(common::is_dynamic_label(labels[i], scheme, changed_is_dynamic) ? 1
                                                                                              : 0);
    }
    return true;
}

DynamicRemovalResult evaluate_dynamic_removal(const LabelledMap& truth,
                                              const std::vector<Eigen::Vector3f>& output_map,
                                              const DynamicRemovalConfig& config) {
    const PointGrid grid(output_map, config.match_distance);
    DynamicRemovalResult r;
    const std::size_t n = std::min(truth.points.size(), truth.dynamic.size());
    for (std::size_t i = 0; i < n; ++i) {
        const bool kept = grid.has_neighbour(truth.points[i]);
        if (truth.dynamic[i]) {
            ++r.dynamic_points;
            if (!kept) ++r.dynamic_removed;
        } else {
            ++r.static_points;
            if (kept) ++r.static_kept;
        }
    }
    if (r.static_points > 0)
        r.sa_pct =
            100.0 * static_cast<double>(r.static_kept) / static_cast<double>(r.static_points);
    if (r.dynamic_points > 0)
        r.da_pct =
            100.0 * static_cast<double>(r.dynamic_removed) / static_cast<double>(r.dynamic_points);
    r.aa_pct = std::sqrt(r.sa_pct * r.da_pct);
    if (r.sa_pct + r.da_pct > 0.0) r.ha_pct = 2.0 * r.sa_pct * r.da_pct / (r.sa_pct + r.da_pct);
    return r;
}

}  // namespace ltm::eval
