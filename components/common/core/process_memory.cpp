#include "common/core/process_memory.hpp"

#include <cstdlib>
#include <fstream>
#include <string>

namespace ltm::common {

ProcessMemory process_memory() {
    ProcessMemory m;
    std::ifstream in("/proc/self/status");
    std::string line;
    while (std::getline(in, line)) {
        if (line.rfind("VmRSS:", 0) == 0) m.resident_mib = std::atof(line.c_str() + 6) / 1024.0;
        if (line.rfind("VmHWM:", 0) == 0) m.peak_mib = std::atof(line.c_str() + 6) / 1024.0;
    }
    return m;
}

}  // namespace ltm::common
