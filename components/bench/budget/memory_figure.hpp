#pragma once
// Memory over time as an SVG figure (standard viewers): resident memory of each host against the
// time since its start, with the budget as a dashed line.
#include <ostream>
#include <string>
#include <vector>

namespace ltm::bench {

struct MemoryCurve {
    std::string label;
    std::vector<double> t_s;     // since the host's start
    std::vector<double> rss_mb;  // resident memory
};

void write_memory_svg(std::ostream& out, const std::string& title,
                      const std::vector<MemoryCurve>& curves, double budget_mb);

}  // namespace ltm::bench
