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
    // The points in the map frame at the pose; an offset only adds to them.
    std::vector<Eigen::Vector3f> at;
    const double stride = std::max(1.0, double(points.size()) / double(config.points));
    const Eigen::Matrix3f R = T_map_lidar.linear().cast<float>();
    const Eigen::Vector3f t = T_map_lidar.translation().cast<float>();
    for (double i = 0.0; i < double(points.size()); i += stride)
        at.push_back(R * points[std::size_t(i)] + t);
    const float on_surface = float(0.75 * config.step);
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
    best.share_at_start = best.share = share_at(Eigen::Vector3f::Zero());
    const int n = int(std::floor(config.radius / config.step));
    for (int ix = -n; ix <= n; ++ix) {
        for (int iy = -n; iy <= n; ++iy) {
            const double dx = ix * config.step, dy = iy * config.step;
            const double offset = std::hypot(dx, dy);
            if (offset == 0.0 || offset > config.radius + 1e-9) continue;
            const double share = share_at(Eigen::Vector3f(float(dx), float(dy), 0.0f));
            if (share > best.share || (share == best.share && offset < best.offset)) {
                best.share = share;
                best.offset = offset;
                best.T_map_lidar = T_map_lidar;
                best.T_map_lidar.translation() += Eigen::Vector3d(dx, dy, 0.0);
            }
        }
    }
    return best;
}

}  // namespace ltm::localisation
