#pragma once
// The arithmetic of `./ltm bench budget`: CPU time per component and role over the samples of a
// host, its share of one core (on average and in the worst window), percentiles, and the
// matching of the probe's scans with the poses and map updates they led to.
#include <cstdint>
#include <istream>
#include <map>
#include <ostream>
#include <string>
#include <vector>

#include "bench/budget/proc_stat.hpp"

namespace ltm::bench {

// --- the monitor's samples file: "hz H", then per sample "s T PROCESS_TICKS RSS_KB HWM_KB" and a
// "w TID TICKS WAIT_NS NAME" line per thread (older files: "t TID TICKS NAME", no wait).
void write_sample(std::ostream& out, const ProcessSample& s);
struct SampleLog {
    long hz = 100;
    bool has_wait = false;  // "w" lines: the run-queue wait was sampled
    std::vector<ProcessSample> samples;
};
SampleLog read_samples(std::istream& in);  // throws std::runtime_error naming the bad line

// Cumulative CPU time [s] at each sample time, and the time runnable but waiting for a core [s].
struct CpuSeries {
    std::vector<double> t, cpu_s, wait_s;
};

// Per owner ("component/role", thread_owner's key) and "process" (CPU: /proc/PID/stat, exited
// threads too; wait: the threads' sum). A thread that ended keeps the times it had when last seen.
std::map<std::string, CpuSeries> cpu_by_owner(const SampleLog& log,
                                              const std::vector<std::string>& components);
// Sums series of the same times (e.g. every role of one component).
CpuSeries sum_series(const std::vector<const CpuSeries*>& parts);

double cpu_at(const CpuSeries& s, double t);   // linear between samples, clamped to the ends
double wait_at(const CpuSeries& s, double t);  // the same of the run-queue wait
// CPU seconds per wall second over [t0, t1] (1.0 = one core).
double average_share(const CpuSeries& s, double t0, double t1);
// The largest share over windows of `window_s` starting at a sample inside [t0, t1 - window_s].
double worst_window_share(const CpuSeries& s, double t0, double t1, double window_s = 1.0);
// The starts of the `n` worst windows of `window_s` in [t0, t1] that do not overlap, worst first
// (what made the bursts: each one's CPU per owner is then cpu_at(start + window) - cpu_at(start)).
struct Window {
    double start = 0, share = 0;
};
std::vector<Window> worst_windows(const CpuSeries& s, double t0, double t1, std::size_t n,
                                  double window_s = 1.0);
// Whole seconds [t0 + k, t0 + k + 1) inside [t0, t1] in which the share was at least `threshold`
// (a burst: a maintenance pass holding a core).
int busy_seconds(const CpuSeries& s, double t0, double t1, double threshold = 0.9);
// Linear between the closest ranks (p in [0, 100]); 0 for an empty set.
double percentile(std::vector<double> values, double p);

// --- the probe's records: "topic,stamp,sent,received" (s; sent = the writer's source timestamp).
struct ProbeRecord {
    std::string topic;
    double stamp = 0, sent = 0, received = 0;
};
std::vector<ProbeRecord> read_probe(std::istream& in);  // throws std::runtime_error
std::vector<ProbeRecord> of_topic(const std::vector<ProbeRecord>& all, const std::string& topic);

// The span the targets name: from the first scan's publish to the last's + 1 s (its processing),
// within the host's samples [first_sample, last_sample]; it ends sooner at `shutdown` (wall clock,
// s; 0: unknown) when the host began its shutdown before that (the end-of-session pass and the
// saves are the stop, not the mission). Without scans: the samples' span.
struct MissionSpan {
    double t0 = 0, t1 = 0;
    bool ends_at_shutdown = false;
};
MissionSpan mission_span(double first_sample, double last_sample,
                         const std::vector<ProbeRecord>& scans, double shutdown);

struct Delivery {
    std::size_t scans = 0;          // scans the probe saw published
    std::size_t missing = 0;        // with no output for them
    std::vector<double> latency_s;  // sent(output) - sent(scan), one per matched scan
};
// Each scan's output of the same stamp (within 1 us).
Delivery match_by_stamp(const std::vector<ProbeRecord>& scans,
                        const std::vector<ProbeRecord>& outputs);
// Each scan's first update sent after it whose stamp is not older (a maintenance pass that
// took it in); scans after the last update are `missing`.
Delivery match_next_update(const std::vector<ProbeRecord>& scans,
                           const std::vector<ProbeRecord>& updates);

}  // namespace ltm::bench
