#include "registration/core/registration_target.hpp"

namespace ltm::registration {

RegistrationTarget make_registration_target(const common::LocalMapData& data, double min_planarity,
                                            int coarse_factor) {
    const registration::VoxelConfig config;  // further integration: the odometry's defaults
    std::size_t skipped = 0;
    RegistrationTarget t{registration::VoxelGrid::from_data(data, config, min_planarity, &skipped),
                         std::nullopt, data.T_anchor_grid, skipped};
    if (coarse_factor >= 2) t.coarse.emplace(t.fine.coarsened(coarse_factor, config));
    return t;
}

}  // namespace ltm::registration
