#include "evaluation/core/new_ground.hpp"

#include "evaluation/core/point_grid.hpp"

namespace ltm::eval {

double new_ground_length(const std::vector<Eigen::Vector3d>& path,
                         const std::vector<Eigen::Vector3d>& earlier,
                         const NewGroundConfig& config) {
    if (path.size() < 2) return 0.0;
    auto flat = [](const Eigen::Vector3d& p) {
        return Eigen::Vector3f(static_cast<float>(p.x()), static_cast<float>(p.y()), 0.0f);
    };
    std::vector<Eigen::Vector3f> before;
    before.reserve(earlier.size());
    for (const auto& p : earlier) before.push_back(flat(p));
    const PointGrid grid(before, config.radius);
    std::vector<bool> is_new(path.size());
    for (std::size_t i = 0; i < path.size(); ++i)
        is_new[i] = before.empty() || !grid.has_neighbour(flat(path[i]));
    double length = 0.0;
    for (std::size_t i = 1; i < path.size(); ++i) {
        const double step = (path[i].head<2>() - path[i - 1].head<2>()).norm();
        if (is_new[i] && is_new[i - 1] && step <= config.max_step) length += step;
    }
    return length;
}

}  // namespace ltm::eval
