#include "bench/budget/proc_stat.hpp"

#include <dirent.h>
#include <time.h>
#include <unistd.h>

#include <fstream>
#include <sstream>

namespace ltm::bench {

std::optional<TaskStat> parse_task_stat(const std::string& line) {
    const auto open = line.find('(');
    const auto close = line.rfind(')');
    if (open == std::string::npos || close == std::string::npos || close < open) return {};
    TaskStat s;
    try {
        s.tid = std::stoi(line.substr(0, open));
    } catch (...) {
        return {};
    }
    s.name = line.substr(open + 1, close - open - 1);
    // After ") ": field 3 (state) on; utime and stime are fields 14 and 15.
    std::istringstream rest(line.substr(close + 1));
    std::string field;
    std::uint64_t utime = 0, stime = 0;
    for (int f = 3; f <= 15; ++f) {
        if (!(rest >> field)) return {};
        try {
            if (f == 14) utime = std::stoull(field);
            if (f == 15) stime = std::stoull(field);
        } catch (...) {
            return {};
        }
    }
    s.ticks = utime + stime;
    return s;
}

std::optional<std::uint64_t> parse_schedstat_wait(const std::string& text) {
    std::istringstream in(text);
    std::uint64_t run = 0, wait = 0;
    if (!(in >> run >> wait)) return {};
    return wait;
}

std::optional<ProcessMemory> parse_status(const std::string& text) {
    ProcessMemory m;
    bool rss = false, hwm = false;
    std::istringstream in(text);
    std::string line;
    while (std::getline(in, line)) {
        const bool is_rss = line.rfind("VmRSS:", 0) == 0, is_hwm = line.rfind("VmHWM:", 0) == 0;
        if (!is_rss && !is_hwm) continue;
        std::istringstream v(line.substr(6));
        std::uint64_t kb = 0;
        std::string unit;
        if (!(v >> kb >> unit) || unit != "kB") return {};
        (is_rss ? m.rss_kb : m.hwm_kb) = kb;
        (is_rss ? rss : hwm) = true;
    }
    if (!rss || !hwm) return {};
    return m;
}

namespace {
std::optional<std::string> read_text(const std::string& path) {
    std::ifstream in(path);
    if (!in) return {};
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}
}  // namespace

std::optional<ProcessSample> sample_process(int pid) {
    ProcessSample s;
    s.t = realtime_now_s();
    const std::string dir = "/proc/" + std::to_string(pid);
    const auto stat = read_text(dir + "/stat");
    const auto status = read_text(dir + "/status");
    if (!stat || !status) return {};
    const auto ps = parse_task_stat(*stat);
    const auto mem = parse_status(*status);
    if (!ps || !mem) return {};
    s.process_ticks = ps->ticks;
    s.memory = *mem;
    DIR* d = opendir((dir + "/task").c_str());
    if (!d) return {};
    while (dirent* e = readdir(d)) {
        if (e->d_name[0] == '.') continue;
        const auto ts = read_text(dir + "/task/" + e->d_name + "/stat");
        if (!ts) continue;  // the thread ended meanwhile
        auto t = parse_task_stat(*ts);
        if (!t) continue;
        if (const auto sched = read_text(dir + "/task/" + e->d_name + "/schedstat"))
            t->wait_ns = parse_schedstat_wait(*sched).value_or(0);
        s.threads.push_back(*t);
    }
    closedir(d);
    return s;
}

long clock_ticks_per_second() { return sysconf(_SC_CLK_TCK); }

double realtime_now_s() {
    timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

}  // namespace ltm::bench
