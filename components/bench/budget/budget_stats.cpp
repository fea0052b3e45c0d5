#include "bench/budget/budget_stats.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include "bench/budget/thread_owner.hpp"

namespace ltm::bench {

void write_sample(std::ostream& out, const ProcessSample& s) {
    out << "s " << std::fixed << std::setprecision(6) << s.t << ' ' << s.process_ticks << ' '
        << s.memory.rss_kb << ' ' << s.memory.hwm_kb << '\n';
    for (const auto& t : s.threads)
        out << "w " << t.tid << ' ' << t.ticks << ' ' << t.wait_ns << ' ' << t.name << '\n';
}

SampleLog read_samples(std::istream& in) {
    SampleLog log;
    std::string line;
    int n = 0;
    while (std::getline(in, line)) {
        ++n;
        if (line.empty()) continue;
        std::istringstream f(line);
        std::string kind;
        f >> kind;
        bool ok = true;
        if (kind == "hz") {
            ok = bool(f >> log.hz) && log.hz > 0;
        } else if (kind == "s") {
            ProcessSample s;
            ok = bool(f >> s.t >> s.process_ticks >> s.memory.rss_kb >> s.memory.hwm_kb);
            if (ok) log.samples.push_back(s);
        } else if ((kind == "t" || kind == "w") && !log.samples.empty()) {
            TaskStat t;
            ok = bool(f >> t.tid >> t.ticks);
            if (ok && kind == "w") {
                ok = bool(f >> t.wait_ns);
                log.has_wait = true;
            }
            if (ok) {
                f.get();  // the one space before the name (which may hold spaces)
                std::getline(f, t.name);
                log.samples.back().threads.push_back(t);
            }
        } else {
            ok = false;
        }
        if (!ok) throw std::runtime_error("samples line " + std::to_string(n) + ": '" + line + "'");
    }
    return log;
}

std::map<std::string, CpuSeries> cpu_by_owner(const SampleLog& log,
                                              const std::vector<std::string>& components) {
    std::map<std::string, CpuSeries> out;
    std::map<std::pair<int, std::string>, std::pair<std::uint64_t, std::uint64_t>>
        last;  // (tid, name): ticks, wait_ns
    std::map<std::pair<int, std::string>, std::string> key_of;
    std::map<std::string, bool> keys;
    for (const auto& s : log.samples)
        for (const auto& t : s.threads) {
            auto k = std::make_pair(t.tid, t.name);
            if (!key_of.count(k)) key_of[k] = thread_owner(t.name, components).key();
            keys[key_of[k]] = true;
        }
    const double hz = double(log.hz);
    for (const auto& s : log.samples) {
        for (const auto& t : s.threads) last[{t.tid, t.name}] = {t.ticks, t.wait_ns};
        std::map<std::string, std::pair<std::uint64_t, std::uint64_t>> sum;
        std::uint64_t all_wait = 0;
        for (const auto& [k, v] : last) {
            sum[key_of[k]].first += v.first;
            sum[key_of[k]].second += v.second;
            all_wait += v.second;
        }
        for (const auto& [key, unused] : keys) {
            (void)unused;
            auto& series = out[key];
            series.t.push_back(s.t);
            series.cpu_s.push_back(sum.count(key) ? sum[key].first / hz : 0.0);
            series.wait_s.push_back(sum.count(key) ? 1e-9 * double(sum[key].second) : 0.0);
        }
        auto& p = out["process"];
        p.t.push_back(s.t);
        p.cpu_s.push_back(s.process_ticks / hz);
        p.wait_s.push_back(1e-9 * double(all_wait));
    }
    return out;
}

CpuSeries sum_series(const std::vector<const CpuSeries*>& parts) {
    CpuSeries out;
    if (parts.empty()) return out;
    out = *parts[0];
    for (std::size_t p = 1; p < parts.size(); ++p) {
        if (parts[p]->cpu_s.size() != out.cpu_s.size())
            throw std::invalid_argument("sum_series: series of different lengths");
        for (std::size_t i = 0; i < out.cpu_s.size(); ++i) {
            out.cpu_s[i] += parts[p]->cpu_s[i];
            if (i < out.wait_s.size() && i < parts[p]->wait_s.size())
                out.wait_s[i] += parts[p]->wait_s[i];
        }
    }
    return out;
}

namespace {
double value_at(const std::vector<double>& times, const std::vector<double>& v, double t) {
    if (times.empty() || v.size() != times.size()) return 0.0;
    if (t <= times.front()) return v.front();
    if (t >= times.back()) return v.back();
    const auto it = std::upper_bound(times.begin(), times.end(), t);
    const std::size_t i = std::size_t(it - times.begin());
    const double a = (t - times[i - 1]) / (times[i] - times[i - 1]);
    return v[i - 1] + a * (v[i] - v[i - 1]);
}
}  // namespace

double cpu_at(const CpuSeries& s, double t) { return value_at(s.t, s.cpu_s, t); }
double wait_at(const CpuSeries& s, double t) { return value_at(s.t, s.wait_s, t); }

double average_share(const CpuSeries& s, double t0, double t1) {
    if (t1 <= t0) return 0.0;
    return (cpu_at(s, t1) - cpu_at(s, t0)) / (t1 - t0);
}

double worst_window_share(const CpuSeries& s, double t0, double t1, double window_s) {
    double worst = 0.0;
    for (std::size_t i = 0; i < s.t.size(); ++i) {
        if (s.t[i] < t0 || s.t[i] + window_s > t1) continue;
        worst = std::max(worst, (cpu_at(s, s.t[i] + window_s) - s.cpu_s[i]) / window_s);
    }
    return worst;
}

std::vector<Window> worst_windows(const CpuSeries& s, double t0, double t1, std::size_t n,
                                  double window_s) {
    std::vector<Window> all;
    for (std::size_t i = 0; i < s.t.size(); ++i) {
        if (s.t[i] < t0 || s.t[i] + window_s > t1) continue;
        all.push_back({s.t[i], (cpu_at(s, s.t[i] + window_s) - s.cpu_s[i]) / window_s});
    }
    std::stable_sort(all.begin(), all.end(),
                     [](const Window& a, const Window& b) { return a.share > b.share; });
    std::vector<Window> out;
    for (const Window& w : all) {
        if (out.size() >= n) break;
        bool overlaps = false;
        for (const Window& o : out) overlaps = overlaps || std::abs(o.start - w.start) < window_s;
        if (!overlaps) out.push_back(w);
    }
    return out;
}

int busy_seconds(const CpuSeries& s, double t0, double t1, double threshold) {
    int n = 0;
    for (double t = t0; t + 1.0 <= t1 + 1e-9; t += 1.0)
        if (cpu_at(s, t + 1.0) - cpu_at(s, t) >= threshold) ++n;
    return n;
}

double percentile(std::vector<double> v, double p) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    const double r = std::clamp(p, 0.0, 100.0) / 100.0 * double(v.size() - 1);
    const std::size_t lo = std::size_t(std::floor(r)), hi = std::min(lo + 1, v.size() - 1);
    return v[lo] + (r - double(lo)) * (v[hi] - v[lo]);
}

std::vector<ProbeRecord> read_probe(std::istream& in) {
    std::vector<ProbeRecord> out;
    std::string line;
    int n = 0;
    while (std::getline(in, line)) {
        ++n;
        if (line.empty() || line.rfind("topic,", 0) == 0) continue;
        std::istringstream f(line);
        ProbeRecord r;
        std::string stamp, sent, received;
        if (!std::getline(f, r.topic, ',') || !std::getline(f, stamp, ',') ||
            !std::getline(f, sent, ',') || !std::getline(f, received))
            throw std::runtime_error("probe line " + std::to_string(n) + ": '" + line + "'");
        try {
            r.stamp = std::stod(stamp);
            r.sent = std::stod(sent);
            r.received = std::stod(received);
        } catch (...) {
            throw std::runtime_error("probe line " + std::to_string(n) + ": '" + line + "'");
        }
        out.push_back(r);
    }
    return out;
}

std::vector<ProbeRecord> of_topic(const std::vector<ProbeRecord>& all, const std::string& topic) {
    std::vector<ProbeRecord> out;
    for (const auto& r : all)
        if (r.topic == topic) out.push_back(r);
    return out;
}

Delivery match_by_stamp(const std::vector<ProbeRecord>& scans,
                        const std::vector<ProbeRecord>& outputs) {
    std::map<long long, double> sent;  // stamp [us]: the first output's sent time
    for (const auto& o : outputs) sent.emplace(std::llround(o.stamp * 1e6), o.sent);
    Delivery d;
    d.scans = scans.size();
    for (const auto& s : scans) {
        const auto it = sent.find(std::llround(s.stamp * 1e6));
        if (it == sent.end()) {
            ++d.missing;
            continue;
        }
        d.latency_s.push_back(it->second - s.sent);
    }
    return d;
}

Delivery match_next_update(const std::vector<ProbeRecord>& scans,
                           const std::vector<ProbeRecord>& updates) {
    std::vector<ProbeRecord> u = updates;
    std::sort(u.begin(), u.end(),
              [](const ProbeRecord& a, const ProbeRecord& b) { return a.sent < b.sent; });
    Delivery d;
    d.scans = scans.size();
    for (const auto& s : scans) {
        const auto it = std::find_if(u.begin(), u.end(), [&](const ProbeRecord& r) {
            return r.sent >= s.sent && r.stamp >= s.stamp - 1e-6;
        });
        if (it == u.end()) {
            ++d.missing;
            continue;
        }
        d.latency_s.push_back(it->sent - s.sent);
    }
    return d;
}

MissionSpan mission_span(double first_sample, double last_sample,
                         const std::vector<ProbeRecord>& scans, double shutdown) {
    MissionSpan m{first_sample, last_sample, false};
    if (!scans.empty()) {
        double first = scans.front().sent, last = scans.front().sent;
        for (const auto& s : scans) {
            first = std::min(first, s.sent);
            last = std::max(last, s.sent);
        }
        m.t0 = std::max(m.t0, first);
        m.t1 = std::min(m.t1, last + 1.0);
    }
    if (shutdown > m.t0 && shutdown < m.t1) {
        m.t1 = shutdown;
        m.ends_at_shutdown = true;
    }
    return m;
}

}  // namespace ltm::bench
