#pragma once
// What `./ltm bench budget` reads of a running process from /proc: each thread's name and CPU
// time (/proc/PID/task/TID/stat), the process's CPU time (/proc/PID/stat, exited threads
// included) and its memory (/proc/PID/status: VmRSS now, VmHWM the peak so far).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace ltm::bench {

struct TaskStat {
    int tid = 0;
    std::string name;           // comm: the thread's name (15 characters at most)
    std::uint64_t ticks = 0;    // utime + stime [clock ticks]
    std::uint64_t wait_ns = 0;  // time runnable but waiting for a core (/proc/.../schedstat)
};

struct ProcessMemory {
    std::uint64_t rss_kb = 0;  // VmRSS
    std::uint64_t hwm_kb = 0;  // VmHWM: the peak resident set so far
};

// One line of /proc/.../stat; nullopt when it is not one (the name may hold spaces and ')').
std::optional<TaskStat> parse_task_stat(const std::string& line);
// /proc/.../schedstat ("run_ns wait_ns timeslices"): the run-queue wait; nullopt if malformed.
std::optional<std::uint64_t> parse_schedstat_wait(const std::string& text);
// The text of /proc/PID/status; nullopt without VmRSS and VmHWM (a zombie, a kernel thread).
std::optional<ProcessMemory> parse_status(const std::string& text);

struct ProcessSample {
    double t = 0;  // CLOCK_REALTIME [s] (comparable with DDS source timestamps)
    std::uint64_t process_ticks = 0;
    ProcessMemory memory;
    std::vector<TaskStat> threads;
};

// Reads PID's threads, CPU and memory now; nullopt once the process is gone.
std::optional<ProcessSample> sample_process(int pid);
long clock_ticks_per_second();
double realtime_now_s();

}  // namespace ltm::bench
