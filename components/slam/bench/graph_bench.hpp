#pragma once
// Synthetic pose graphs for timing the optimisation: laps of a 1 km loop with anchors every 20 m,
// a drifting odometry, and a loop edge from every other anchor of a later lap to the first lap.
#include <cstddef>
#include <cstdint>

#include "mapping/core/mapper_config.hpp"

namespace ltm::slam::bench {

struct GraphBenchResult {
    std::size_t nodes = 0, edges = 0, loops = 0;
    double first_ms = 0.0;                         // the first optimisation, from the odometry
    double incremental_ms = 0.0;                   // again after one more loop edge (warm start)
    double error_before = 0.0, error_after = 0.0;  // largest anchor position error [m]
    bool solved = false;
    std::size_t loops_rejected = 0;
    int iterations = 0, solves = 0;  // of the first optimisation
};

GraphBenchResult run_graph_bench(std::size_t anchors, const mapping::MapperConfig& config,
                                 std::uint32_t seed = 1);

}  // namespace ltm::slam::bench
