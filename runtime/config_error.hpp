#pragma once
#include "common/core/config_check.hpp"

namespace ltm::runtime {

// A bad launch configuration or parameter: the project's one configuration error
// (common/core/config_check.hpp). what() is the one line the host prints:
// "FILE:LINE: KEY: PROBLEM".
using ConfigError = common::ConfigError;

}  // namespace ltm::runtime
