#pragma once
// The process's memory as the kernel reports it (/proc/self/status), for benchmarks.
namespace ltm::common {

struct ProcessMemory {
    double resident_mib = -1.0;  // VmRSS
    double peak_mib = -1.0;      // VmHWM: the peak resident memory
};

// -1 where unavailable (not Linux).
ProcessMemory process_memory();

}  // namespace ltm::common
