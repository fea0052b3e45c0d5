#pragma once
// Growth per lap, for the SLAM benchmark driving a route N times (--laps): at the end of each lap
// the mapper's memory, the saved map's size on disk, local maps, keyframes, graph nodes and edges,
// loops and the optimisations of that lap; the report gives each lap's growth over the lap
// before (issue 13's target: at most +5 % a lap after the first).
#include <cstddef>
#include <cstdio>
#include <vector>

#include "common/core/trajectory_io.hpp"

namespace ltm::slam::bench {

struct LapSample {
    std::size_t lap = 0, frame = 0;
    double mapper_mib = 0.0;
    double disk_mib = -1.0;  // < 0: not saved
    std::size_t local_maps = 0, keyframes = 0, nodes = 0, edges = 0, loops = 0;
    std::size_t optimisations = 0;  // of this lap
    double optimise_p95_ms = 0.0;   // of this lap's optimisations
    // Against the reference, over every frame so far (< 0: not known).
    double ate_rmse = -1.0, ate_percent = -1.0;  // [m], of the path
    std::size_t revisits = 0, revisits_closed = 0;
    std::size_t longest_unclosed = 0;  // revisiting frames in a row without a loop
};

// The last frame of each lap of a route driven `laps` times, from its reference: a lap after the
// first starts where the reference comes back to its first pose (the nearest frame within 2 m,
// heading within 45 deg) at least 300 frames after the lap before started. The last lap ends with
// the last frame; fewer ends when the reference does not come back.
std::vector<std::size_t> lap_ends(const common::PoseList& reference, std::size_t laps);

class LapGrowthLog {
  public:
    // Stores and prints (to `out`) one sample.
    void add(const LapSample& s, std::FILE* out);
    const std::vector<LapSample>& samples() const { return samples_; }
    // The table with each lap's growth over the one before (memory, disk, local maps, keyframes).
    void report(std::FILE* out) const;

  private:
    std::vector<LapSample> samples_;
};

// The p95 of `v` (0 when empty): the value at index floor(0.95 n) of the sorted values.
double p95(std::vector<double> v);

}  // namespace ltm::slam::bench
