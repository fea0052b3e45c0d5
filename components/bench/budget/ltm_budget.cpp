// ltm_budget: the pieces of `./ltm bench budget` (components/bench/budget/README.md).
//   ltm_budget monitor --pid P --out SAMPLES      samples a host's threads and memory from /proc
//   ltm_budget variant --in L.yaml --out V.yaml    a launch config made into the benchmark's
//   ltm_budget report --host LABEL:SAMPLES:LAUNCH ... [--probe CSV] --out DIR
//   ltm_budget sensor --scans DIR                  the preset, sensor and beams of DIR's scans
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <set>
#include <sstream>
#include <thread>

#include "bench/budget/budget_stats.hpp"
#include "bench/budget/launch_variant.hpp"
#include "bench/budget/memory_figure.hpp"
#include "bench/budget/proc_stat.hpp"
#include "bench/budget/scan_sensor.hpp"
#include "bench/budget/thread_owner.hpp"
#include "common/cli/cli.hpp"

namespace ltm::bench {
namespace {

int monitor(int pid, double interval_s, const std::string& out_path) {
    std::ofstream out(out_path);
    if (!out) {
        std::cerr << "ltm_budget monitor: cannot write " << out_path << "\n";
        return 1;
    }
    out << "hz " << clock_ticks_per_second() << "\n";
    auto next = std::chrono::steady_clock::now();
    std::size_t n = 0;
    while (auto s = sample_process(pid)) {
        write_sample(out, *s);
        out.flush();
        ++n;
        next += std::chrono::duration_cast<std::chrono::steady_clock::duration>(
            std::chrono::duration<double>(interval_s));
        std::this_thread::sleep_until(next);
        if (next < std::chrono::steady_clock::now()) next = std::chrono::steady_clock::now();
    }
    std::cerr << "ltm_budget monitor: " << n << " samples of pid " << pid << " in " << out_path
              << "\n";
    return n > 0 ? 0 : 1;
}

struct HostRun {
    std::string label;
    SampleLog log;
    std::vector<std::string> components;
};

std::string fmt(const char* f, double v) {
    char b[64];
    std::snprintf(b, sizeof b, f, v);
    return b;
}

struct Targets {
    double avg_share = 0.5, window_share = 1.0, latency_p99_s = 0.05, peak_mb = 1024;
};

std::string verdict(bool ok) { return ok ? "meets" : "MISSES"; }

void report_host(std::ostream& out, const HostRun& h, double t0, double t1, bool ends_at_stop,
                 std::size_t scans, const Targets& targets, bool is_robot) {
    const auto series = cpu_by_owner(h.log, h.components);
    const CpuSeries& process = series.at("process");
    const double span = t1 - t0;
    out << "\n## host " << h.label << "\n\n";
    out << "mission span " << fmt("%.1f", span) << " s (first scan published .. "
        << (ends_at_stop ? "the host's shutdown, which began within 1 s of the last scan"
                         : "last + 1 s")
        << "), " << scans << " scans; whole run "
        << fmt("%.1f", h.log.samples.back().t - h.log.samples.front().t)
        << " s (start-up and final saves included)\n\n";
    out << "| component / thread | CPU in span [s] | ms a scan | share of one core avg | worst 1 s "
           "| s at >= 90 % | waiting for a core, ms a scan | CPU whole run [s] |\n";
    out << "|---|---:|---:|---:|---:|---:|---:|---:|\n";
    // Components (their roles summed), then each role.
    std::map<std::string, std::vector<const CpuSeries*>> by_component;
    for (const auto& [key, s] : series) {
        if (key == "process") continue;
        by_component[key.substr(0, key.rfind('/'))].push_back(&s);
    }
    auto row = [&](const std::string& name, const CpuSeries& s) {
        const double cpu = cpu_at(s, t1) - cpu_at(s, t0);
        out << "| " << name << " | " << fmt("%.2f", cpu) << " | "
            << fmt("%.1f", scans ? 1e3 * cpu / double(scans) : 0.0) << " | "
            << fmt("%.1f %%", 100 * average_share(s, t0, t1)) << " | "
            << fmt("%.0f %%", 100 * worst_window_share(s, t0, t1)) << " | "
            << busy_seconds(s, t0, t1) << " | "
            << (h.log.has_wait
                    ? fmt("%.1f",
                          scans ? 1e3 * (wait_at(s, t1) - wait_at(s, t0)) / double(scans) : 0.0)
                    : std::string("-"))
            << " | " << fmt("%.2f", s.cpu_s.back() - s.cpu_s.front()) << " |\n";
    };
    for (const auto& [component, parts] : by_component) {
        const CpuSeries sum = sum_series(parts);
        row("**" + component + "**", sum);
        if (parts.size() > 1 || series.count(component + "/main") == 0)
            for (const auto& [key, s] : series)
                if (key.substr(0, key.rfind('/')) == component) row("&nbsp;&nbsp;" + key, s);
    }
    row("**process** (/proc/PID/stat)", process);
    // What made the bursts: the threads' CPU in the process's worst windows.
    out << "\nthe process's worst 1 s windows (s after the first scan: share; the threads with "
           ">= 5 % of a core in it):\n\n";
    for (const Window& w : worst_windows(process, t0, t1, 5)) {
        out << "- +" << fmt("%.1f", w.start - t0) << " s: " << fmt("%.0f %%", 100 * w.share);
        std::vector<std::pair<double, std::string>> who;
        for (const auto& [key, s] : series) {
            if (key == "process") continue;
            const double share = cpu_at(s, w.start + 1.0) - cpu_at(s, w.start);
            if (share >= 0.05) who.emplace_back(share, key);
        }
        std::sort(who.rbegin(), who.rend());
        for (std::size_t k = 0; k < who.size(); ++k)
            out << (k ? ", " : ": ") << who[k].second << " " << fmt("%.0f %%", 100 * who[k].first);
        out << "\n";
    }
    // The start-up (the components loading the site) and the end (last passes, saves) are outside
    // the mission span: their worst second too, so that a burst moved there is seen.
    const double r0 = h.log.samples.front().t, r1 = h.log.samples.back().t;
    for (const Window& w : worst_windows(process, r0, r1, 1))
        out << "\nover the whole run (start-up and the end included): worst 1 s window "
            << fmt("%.0f %%", 100 * w.share) << " at " << fmt("%+.1f", w.start - t0)
            << " s from the first scan (whole run: " << fmt("%.1f", r0 - t0) << " .. "
            << fmt("%+.1f", r1 - t0) << " s)\n";
    const double avg = average_share(process, t0, t1), worst = worst_window_share(process, t0, t1);
    double peak = 0;
    for (const auto& s : h.log.samples) peak = std::max(peak, s.memory.hwm_kb / 1024.0);
    const double final_mb = h.log.samples.back().memory.rss_kb / 1024.0;
    out << "\nCPU a scan "
        << fmt("%.1f",
               scans ? 1e3 * (cpu_at(process, t1) - cpu_at(process, t0)) / double(scans) : 0.0)
        << " ms; memory: peak (VmHWM) " << fmt("%.0f", peak) << " MB, final "
        << fmt("%.0f", final_mb) << " MB\n\n";
    if (is_robot) {
        out << "- average " << fmt("%.1f %%", 100 * avg)
            << " of one core (target <= " << fmt("%.0f %%", 100 * targets.avg_share)
            << "): " << verdict(avg <= targets.avg_share) << "\n";
        out << "- worst 1 s window " << fmt("%.0f %%", 100 * worst)
            << " (target <= " << fmt("%.0f %%", 100 * targets.window_share)
            << "): " << verdict(worst <= targets.window_share) << "\n";
    }
    out << "- peak memory " << fmt("%.0f", peak)
        << " MB (target <= " << fmt("%.0f", targets.peak_mb)
        << " MB): " << verdict(peak <= targets.peak_mb) << "\n";
}

void report_latency(std::ostream& out, const std::vector<ProbeRecord>& probe,
                    const Targets& targets, std::size_t published, bool with_pose) {
    const auto scans = of_topic(probe, "points");
    out << "\n## scans, poses, map updates (the probe: writers' source timestamps, wall clock)\n\n";
    out << "scans seen by the probe " << scans.size();
    if (published) out << " of " << published << " the player published";
    out << "\n\n";
    auto line = [&](const std::string& what, const Delivery& d, const char* missing_word) {
        out << "- " << what << ": " << d.missing << " of " << d.scans << " scans " << missing_word
            << "; latency p50 " << fmt("%.1f", 1e3 * percentile(d.latency_s, 50)) << " ms, p99 "
            << fmt("%.1f", 1e3 * percentile(d.latency_s, 99)) << " ms, max "
            << fmt("%.1f", 1e3 * percentile(d.latency_s, 100)) << " ms (" << d.latency_s.size()
            << " scans)\n";
    };
    const auto odo = of_topic(probe, "odometry"), pose = of_topic(probe, "pose"),
               changes = of_topic(probe, "map_changes");
    {
        const auto d = match_by_stamp(scans, odo);
        line("odometry (scan -> its odometry pose)", d, "missed (no odometry pose)");
        out << "  - no scan missed by the odometry: " << verdict(d.missing == 0) << "\n";
    }
    if (with_pose || !pose.empty()) {
        const auto d = match_by_stamp(scans, pose);
        line("localisation (scan -> its map pose, `pose`)", d, "skipped (no map pose)");
        out << "  - pose latency p99 " << fmt("%.1f", 1e3 * percentile(d.latency_s, 99))
            << " ms (target <= " << fmt("%.0f", 1e3 * targets.latency_p99_s)
            << " ms): " << verdict(percentile(d.latency_s, 99) <= targets.latency_p99_s) << "\n";
    }
    if (!changes.empty())
        line("map update (scan -> the first maintenance pass after it, `map_changes`)",
             match_next_update(scans, changes), "after the last pass");
}

int report(const std::vector<std::string>& hosts, const std::string& probe_path,
           const std::string& out_dir, const std::string& title, std::size_t published,
           const std::string& note, bool with_pose, double target_share, double mission_end) {
    std::vector<HostRun> runs;
    for (const auto& spec : hosts) {
        const auto a = spec.find(':'), b = spec.find(':', a + 1);
        if (a == std::string::npos || b == std::string::npos)
            throw common::cli::UsageError("--host", "LABEL:SAMPLES:LAUNCH, got '" + spec + "'");
        HostRun h;
        h.label = spec.substr(0, a);
        std::ifstream in(spec.substr(a + 1, b - a - 1));
        if (!in) throw std::runtime_error("cannot read " + spec.substr(a + 1, b - a - 1));
        h.log = read_samples(in);
        if (h.log.samples.size() < 2) throw std::runtime_error(h.label + ": fewer than 2 samples");
        h.components = component_names(YAML::LoadFile(spec.substr(b + 1)));
        runs.push_back(std::move(h));
    }
    std::vector<ProbeRecord> probe;
    if (!probe_path.empty()) {
        std::ifstream in(probe_path);
        if (!in) throw std::runtime_error("cannot read " + probe_path);
        probe = read_probe(in);
    }
    const auto scans = of_topic(probe, "points");
    Targets targets;
    targets.avg_share = target_share;
    std::ostringstream out;
    out << "# " << title << "\n\n" << note << "\n";
    for (std::size_t i = 0; i < runs.size(); ++i) {
        const auto& h = runs[i];
        // The robot's host: its shutdown, when it began before the last scan + 1 s, ends the
        // mission (the whole run's worst second still shows the stop).
        const MissionSpan m = mission_span(h.log.samples.front().t, h.log.samples.back().t, scans,
                                           i == 0 ? mission_end : 0.0);
        report_host(out, h, m.t0, m.t1, m.ends_at_shutdown, scans.size(), targets, i == 0);
    }
    if (!probe.empty()) report_latency(out, probe, targets, published, with_pose);
    std::vector<MemoryCurve> curves;
    for (const auto& h : runs) {
        MemoryCurve c;
        c.label = h.label;
        for (const auto& s : h.log.samples) {
            c.t_s.push_back(s.t - h.log.samples.front().t);
            c.rss_mb.push_back(s.memory.rss_kb / 1024.0);
        }
        curves.push_back(std::move(c));
    }
    std::ofstream svg(out_dir + "/memory.svg");
    write_memory_svg(svg, title + ": resident memory", curves, targets.peak_mb);
    out << "\nmemory over time: " << out_dir << "/memory.svg\n";
    std::ofstream(out_dir + "/report.md") << out.str();
    std::cout << out.str();
    return 0;
}

}  // namespace
}  // namespace ltm::bench

int main(int argc, char** argv) {
    using namespace ltm::bench;
    namespace cli = ltm::common::cli;
    CLI::App app{"The pieces of ./ltm bench budget: sample a host, make a launch variant, report",
                 "ltm_budget"};
    cli::configure(app);
    app.require_subcommand(1);
    int pid = 0;
    double interval = 0.1;
    std::string out, in, replace, scans, probe_file, pose_topic, title = "ltm budget", note,
                                                                 presets_of;
    double target_share = 0.5, mission_end = 0.0;
    std::vector<std::string> hosts, probe_inputs;
    int readers = 1;
    bool with_pose = false;
    std::size_t published = 0;
    auto* mon =
        app.add_subcommand("monitor", "sample a process's threads and memory until it exits");
    mon->add_option("--pid", pid, "the host's pid")->required();
    mon->add_option("--interval", interval, "[s] between samples")->check(cli::positive());
    mon->add_option("--out", out, "the samples file")->required();
    auto* var = app.add_subcommand("variant", "a launch config made into the benchmark's");
    var->add_option("--in", in, "the launch config")->required()->check(CLI::ExistingFile);
    var->add_option("--out", out, "the variant to write")->required();
    var->add_option("--replace", replace, "the component to replace by a kitti_player at its rate");
    var->add_option("--scans", scans, "the scan folder it plays (KITTI layout)");
    var->add_option("--wait-for-readers", readers, "readers of points the player waits for");
    var->add_option("--probe", probe_file, "the probe's CSV (none: no probe)");
    var->add_option("--probe-inputs", probe_inputs, "points odometry pose map_changes");
    var->add_option("--probe-pose", pose_topic, "the topic the probe's pose input reads");
    var->add_option("--presets-of", presets_of,
                    "a folder ltm_sim wrote: every component's sensor preset set to its sensor's");
    auto* sen = app.add_subcommand(
        "sensor", "prints the sensor preset, the sensor and its beams of a folder ltm_sim wrote");
    sen->add_option("--scans", scans, "the folder")->required();
    auto* rep = app.add_subcommand("report", "per component and thread CPU, memory, latency");
    rep->add_option("--host", hosts, "LABEL:SAMPLES:LAUNCH (the first: the robot)")->required();
    rep->add_option("--probe", probe_file, "the probe's CSV");
    rep->add_option("--out", out, "the report's folder")->required()->check(CLI::ExistingDirectory);
    rep->add_option("--title", title, "the report's title");
    rep->add_option("--published", published, "scans the player published (its log)");
    rep->add_option("--note", note, "a line for the report (the machine's load)");
    rep->add_option("--target-share", target_share,
                    "the average share of one core the robot's host may use (issue 28: 0.5 on a "
                    "VLP-32C, 1 on a 64-beam sensor)")
        ->check(cli::positive());
    rep->add_option("--mission-end", mission_end,
                    "[s] wall clock (epoch) when the robot's host began its shutdown: the mission "
                    "span ends there if before the last scan + 1 s")
        ->check(cli::at_least(0.0));
    rep->add_flag("--with-pose", with_pose,
                  "a localisation runs: report its map poses even if none came");
    if (const int code = cli::parse(app, argc, argv); code >= 0) return code;
    try {
        if (*mon) return monitor(pid, interval, out);
        if (*var) {
            VariantOptions o;
            o.replace = replace;
            o.scans = scans;
            o.wait_for_readers = readers;
            o.probe_file = probe_file;
            o.probe_inputs = probe_inputs;
            o.probe_pose_topic = pose_topic;
            if (!presets_of.empty())
                o.preset = ltm::common::to_string(preset_of_sim_model(scans_sim_model(presets_of)));
            if (!replace.empty() && scans.empty())
                throw cli::UsageError("--scans", "needed with --replace");
            YAML::Emitter e;
            e << budget_variant(YAML::LoadFile(in), o);
            std::ofstream(out) << "# made by ltm_budget variant from " << in << "\n"
                               << e.c_str() << "\n";
            return 0;
        }
        if (*sen) {
            const auto preset = preset_of_sim_model(scans_sim_model(scans));
            const auto& row = ltm::common::sensor_preset_row(preset);
            std::cout << row.name << "\t" << row.sensor << "\t" << row.rings << "\n";
            return 0;
        }
        if (*rep)
            return report(hosts, probe_file, out, title, published, note, with_pose, target_share,
                          mission_end);
    } catch (const cli::UsageError& e) {
        return cli::usage_error(app, e);
    } catch (const std::exception& e) {
        std::cerr << "ltm_budget: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
