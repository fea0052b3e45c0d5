#pragma once
// Memory as the map grows, for the SLAM benchmark: one sample every kilometre of path (the
// mapper's own count, the process's resident and peak resident memory, local maps, keyframes,
// loops), printed as it is taken, and the growth per km fitted over the samples after the first
// km (a least-squares slope, so a fixed start-up cost does not count as growth).
#include <cstddef>
#include <cstdio>
#include <vector>

#include "common/core/process_memory.hpp"

namespace ltm::slam::bench {

struct KmSample {
    double km = 0.0;
    std::size_t frame = 0;
    double mapper_mib = 0.0;
    common::ProcessMemory process;
    std::size_t local_maps = 0, keyframes = 0, loops = 0;
};

class KmMemoryLog {
  public:
    explicit KmMemoryLog(double every_km = 1.0) : every_km_(every_km) {}
    // True when `path_m` has passed the next sampling point: the caller then calls add().
    bool due(double path_m) const {
        return path_m >= 1000.0 * every_km_ * double(samples_.size() + 1);
    }
    // Stores and prints (to `out`) one sample.
    void add(const KmSample& s, std::FILE* out);
    const std::vector<KmSample>& samples() const { return samples_; }
    // The table and the slopes (MiB/km of mapper and resident memory over km >= 1).
    void report(std::FILE* out) const;

  private:
    double every_km_;
    std::vector<KmSample> samples_;
};

// Least-squares slope of y over x; 0 with fewer than two distinct x.
double fit_slope(const std::vector<double>& x, const std::vector<double>& y);

}  // namespace ltm::slam::bench
