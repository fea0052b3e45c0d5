#include "registration/core/registration_config.hpp"

namespace ltm::registration {

// visit_fields takes a mutable config (loaders write through it): each check visits a copy.

std::optional<common::ConfigProblem> validate(const PreprocessConfig& config) {
    PreprocessConfig c = config;
    common::ConfigChecker k;
    visit_fields(c, "", k);
    k.require(c.max_range > c.min_range, "max_range", "must exceed min_range");
    return k.problem();
}

std::optional<common::ConfigProblem> validate(const VoxelConfig& config) {
    VoxelConfig c = config;
    common::ConfigChecker k;
    visit_fields(c, "", k);
    k.require(c.max_points >= c.min_points_for_normal, "max_points",
              "must be >= min_points_for_normal (" + std::to_string(c.min_points_for_normal) + ")");
    return k.problem();
}

std::optional<common::ConfigProblem> validate(const RegistrationConfig& config) {
    RegistrationConfig c = config;
    common::ConfigChecker k;
    visit_fields(c, "", k);
    return k.problem();
}

}  // namespace ltm::registration
