#include "evaluation/core/new_ground.hpp"

#include "evaluation/core/point_grid.hpp"

namespace ltm::eval {

NewGround new_ground(const std::vector<Eigen::Vector3d>& path,
                     const std::vector<Eigen::Vector3d>& earlier,
                     const std::vector<Eigen::Vector3d>& map, const NewGroundConfig& config) {
    NewGround out;
    if (path.size() < 2) return out;
    auto flat = [](const Eigen::Vector3d& p) {
        return Eigen::Vector3f(static_cast<float>(p.x()), static_cast<float>(p.y()), 0.0f);
    };
    std::vector<Eigen::Vector3f> before, voxels;
    before.reserve(earlier.size());
    for (const auto& p : earlier) before.push_back(flat(p));
    voxels.reserve(map.size());
    for (const auto& p : map) voxels.push_back(p.cast<float>());
    const PointGrid grid(before, config.radius), map_grid(voxels, config.map_radius);
    std::vector<bool> is_new(path.size()), mapped(path.size());
    for (std::size_t i = 0; i < path.size(); ++i) {
        is_new[i] = before.empty() || !grid.has_neighbour(flat(path[i]));
        mapped[i] = is_new[i] && !voxels.empty() && map_grid.has_neighbour(path[i].cast<float>());
    }
    for (std::size_t i = 1; i < path.size(); ++i) {
        const double step = (path[i].head<2>() - path[i - 1].head<2>()).norm();
        if (!is_new[i] || !is_new[i - 1] || step > config.max_step) continue;
        out.driven += step;
        if (mapped[i] && mapped[i - 1]) out.mapped += step;
    }
    return out;
}

}  // namespace ltm::eval
