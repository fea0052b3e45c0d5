#include "localisation/core/translation_search.hpp"

#include <algorithm>
#include <cmath>

namespace ltm::localisation {

TranslationSearchResult search_translation(const std::vector<Eigen::Vector3f>& points,
                                           const registration::VoxelGrid& grid,
                                           const registration::ImlsParams& imls,
                                           const Eigen::Isometry3d& T_map_lidar,
                                           const TranslationSearchConfig& config) {
    TranslationSearchResult best;
    best.T_map_lidar = T_map_lidar;
    if (points.empty() || !(config.step > 0.0)) return best;
    // The points about the pose's origin in the map's axes at each yaw; an offset only adds.
    std::vector<Eigen::Vector3f> sampled;
    const double stride = std::max(1.0, double(points.size()) / double(config.points));
    for (double i = 0.0; i < double(points.size()); i += stride)
        sampled.push_back(points[std::size_t(i)]);
    const Eigen::Vector3f t = T_map_lidar.translation().cast<float>();
    const float on_surface = float(0.75 * config.step);
    std::vector<Eigen::Vector3f> at(sampled.size());
    auto share_at = [&](const Eigen::Vector3f& d) {
        std::size_t on = 0;
        registration::ImlsResult r;
        for (const Eigen::Vector3f& p : at) {
            // On structure only: the ground fits at every offset and would flatten the score.
            if (registration::imls_distance(grid, p + d, imls, &r) &&
                std::abs(r.normal.z()) < 0.8f && std::abs(r.distance) <= on_surface)
                ++on;
        }
        return double(on) / double(at.size());
    };
    auto turn = [&](const Eigen::Matrix3d& R) {
        const Eigen::Matrix3f Rf = R.cast<float>();
        for (std::size_t k = 0; k < sampled.size(); ++k) at[k] = Rf * sampled[k] + t;
    };
    turn(T_map_lidar.linear());
    best.share_at_start = best.share = share_at(Eigen::Vector3f::Zero());
    best.scored = 1;
    const int n = int(std::floor(config.radius / config.step));
    for (const double yaw_deg : config.yaw_offsets) {
        const Eigen::Matrix3d R =
            Eigen::AngleAxisd(yaw_deg * M_PI / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix() *
            T_map_lidar.linear();
        turn(R);
        for (int ix = -n; ix <= n; ++ix) {
            for (int iy = -n; iy <= n; ++iy) {
                const double dx = ix * config.step, dy = iy * config.step;
                const double offset = std::hypot(dx, dy);
                if (offset > config.radius + 1e-9 || (offset == 0.0 && yaw_deg == 0.0)) continue;
                const double share = share_at(Eigen::Vector3f(float(dx), float(dy), 0.0f));
                ++best.scored;
                // Ties go to the smaller change: the smaller offset, then the smaller yaw.
                const bool smaller =
                    offset < best.offset ||
                    (offset == best.offset && std::abs(yaw_deg) < std::abs(best.yaw));
                if (share > best.share || (share == best.share && smaller)) {
                    best.share = share;
                    best.offset = offset;
                    best.yaw = yaw_deg;
                    best.T_map_lidar = T_map_lidar;
                    best.T_map_lidar.linear() = R;
                    best.T_map_lidar.translation() += Eigen::Vector3d(dx, dy, 0.0);
                }
            }
        }
    }
    return best;
}

}  // namespace ltm::localisation
