#include "slam/bench/km_memory.hpp"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <string>

namespace ltm::slam::bench {

double fit_slope(const std::vector<double>& x, const std::vector<double>& y) {
    const std::size_t n = std::min(x.size(), y.size());
    if (n < 2) return 0.0;
    double mx = 0, my = 0;
    for (std::size_t i = 0; i < n; ++i) {
        mx += x[i];
        my += y[i];
    }
    mx /= double(n);
    my /= double(n);
    double sxy = 0, sxx = 0;
    for (std::size_t i = 0; i < n; ++i) {
        sxy += (x[i] - mx) * (y[i] - my);
        sxx += (x[i] - mx) * (x[i] - mx);
    }
    return sxx > 0 ? sxy / sxx : 0.0;
}

void KmMemoryLog::add(const KmSample& s, std::FILE* out) {
    samples_.push_back(s);
    std::fprintf(out,
                 "at %.2f km (frame %zu): mapper %.1f MiB, resident %.1f MiB (peak %.1f), "
                 "%zu local maps, %zu keyframes, %zu loops\n",
                 s.km, s.frame, s.mapper_mib, s.process.resident_mib, s.process.peak_mib,
                 s.local_maps, s.keyframes, s.loops);
    std::fflush(out);
}

void KmMemoryLog::report(std::FILE* out) const {
    if (samples_.empty()) {
        std::fprintf(out, "memory per km: the path is shorter than %.1f km\n", every_km_);
        return;
    }
    std::fprintf(out,
                 "memory by km:\n     km    frame  mapper MiB  resident MiB  peak MiB  "
                 "local maps  keyframes  loops\n");
    std::vector<double> km, mapper, resident;
    for (const KmSample& s : samples_) {
        std::fprintf(out, "  %5.2f  %7zu  %10.1f  %12.1f  %8.1f  %10zu  %9zu  %5zu\n", s.km,
                     s.frame, s.mapper_mib, s.process.resident_mib, s.process.peak_mib,
                     s.local_maps, s.keyframes, s.loops);
        if (s.km >= 1.0 - 1e-9) {
            km.push_back(s.km);
            mapper.push_back(s.mapper_mib);
            resident.push_back(s.process.resident_mib);
        }
    }
    if (km.size() < 2) {
        std::fprintf(out, "memory per km: too few samples after the first km for a slope\n");
        return;
    }
    std::fprintf(out,
                 "memory per km (slope of a least-squares fit over %.2f..%.2f km, %zu samples): "
                 "mapper %.1f MiB/km, resident %.1f MiB/km\n",
                 km.front(), km.back(), km.size(), fit_slope(km, mapper), fit_slope(km, resident));
}

}  // namespace ltm::slam::bench
