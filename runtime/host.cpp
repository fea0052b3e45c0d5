#include "runtime/host.hpp"

#include <malloc.h>
#include <signal.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <thread>

#include "common/core/io_error.hpp"
#include "runtime/config_error.hpp"
#include "runtime/heap_trim.hpp"
#include "runtime/held_memory.hpp"
#include "runtime/log_file.hpp"
#include "runtime/logging.hpp"
#include "runtime/systemd_notify.hpp"

namespace ltm::runtime {
namespace {

Logger g_log("host");

std::string seconds_text(double s) {
    char buf[32];
    std::snprintf(buf, sizeof buf, s < 10 ? "%.1f s" : "%.0f s", s);
    return buf;
}

// Feeds systemd's watchdog every third of its interval while every component makes progress
// (waiting for input counts; one handler, timer or stop step running for more than half the
// interval does not): a component stuck in a loop gets the service restarted.
class Watchdog {
  public:
    Watchdog(const SystemdNotifier& systemd,
             const std::vector<std::unique_ptr<ComponentRunner>>& runners)
        : systemd_(systemd), runners_(runners), interval_(systemd.watchdog_interval()) {}
    void poll() {
        if (interval_.count() <= 0) return;
        const auto now = std::chrono::steady_clock::now();
        if (now < next_) return;
        next_ = now + interval_ / 3;
        for (const auto& r : runners_) {
            if (!r->making_progress(interval_ / 2)) {
                if (stuck_ != r->name())
                    g_log.error("watchdog: component '" + r->name() + "' makes no progress (in " +
                                r->activity() + "); systemd's watchdog is no longer fed");
                stuck_ = r->name();
                return;
            }
        }
        stuck_.clear();
        systemd_.notify("WATCHDOG=1");
    }

  private:
    const SystemdNotifier& systemd_;
    const std::vector<std::unique_ptr<ComponentRunner>>& runners_;
    std::chrono::microseconds interval_;
    std::chrono::steady_clock::time_point next_{};
    std::string stuck_;
};

}  // namespace

void block_stop_signals() {
    // A shell starts background jobs with SIGINT ignored; an ignored signal is discarded even while
    // blocked, so restore the default action first: the host waits for both with sigtimedwait.
    signal(SIGINT, SIG_DFL);
    signal(SIGTERM, SIG_DFL);
    sigset_t set;
    sigemptyset(&set);
    sigaddset(&set, SIGINT);
    sigaddset(&set, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &set, nullptr);
}

void tune_malloc_for_large_samples() {
    mallopt(M_MMAP_THRESHOLD, 64 * 1024 * 1024);
    mallopt(M_TRIM_THRESHOLD, 256 * 1024 * 1024);
    if (!std::getenv("MALLOC_ARENA_MAX"))
        mallopt(M_ARENA_MAX, int(std::max(2u, std::thread::hardware_concurrency())));
}

Host::Host(LaunchConfig config) : config_(std::move(config)) {
    const auto t0 = std::chrono::steady_clock::now();
    // Unknown types are reported before the participant exists.
    for (const auto& spec : config_.components) {
        if (!ComponentRegistry::instance().find(spec.type)) {
            std::string known;
            for (const auto* i : ComponentRegistry::instance().all())
                known += (known.empty() ? "" : ", ") + i->type;
            throw ConfigError(config_.file, spec.type_line, spec.name + ".type",
                              "unknown component type '" + spec.type + "' (known: " + known + ")");
        }
    }
    if (!config_.log.file.empty()) {
        try {
            set_log_file(std::make_shared<RotatingLogFile>(config_.log));
        } catch (const common::IoError& e) {
            throw ConfigError(config_.file, config_.log_line, "log.file", e.what());
        }
    }
    domain_ = std::make_unique<Domain>(config_);
    for (const auto& spec : config_.components)
        runners_.push_back(std::make_unique<ComponentRunner>(
            *domain_, config_, spec, *ComponentRegistry::instance().find(spec.type)));
    startup_ms_ =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

Host::~Host() {
    runners_.clear();  // before the domain
    domain_.reset();
}

bool Host::all_drained() {
    std::uint64_t total = 0;
    for (const auto& r : runners_) {
        if (!r->idle()) {
            drained_polls_ = 0;
            return false;
        }
        total += r->dispatched();
    }
    drained_polls_ = (total == last_dispatched_) ? drained_polls_ + 1 : 0;
    last_dispatched_ = total;
    return drained_polls_ >= 2;
}

bool Host::handle_failures(int& exit_code) {
    for (auto& r : runners_) {
        if (!r->failed()) continue;
        r->wait_done(std::chrono::steady_clock::now() + std::chrono::seconds(2));
        const std::string name = r->name();
        if (config_.on_error == ErrorPolicy::kRestart && restarts_[name] < config_.max_restarts) {
            ++restarts_[name];
            g_log.warn("restarting component '" + name + "' (" + std::to_string(restarts_[name]) +
                       " of " + std::to_string(config_.max_restarts) + ")");
            const ComponentSpec* spec = nullptr;
            for (const auto& s : config_.components)
                if (s.name == name) spec = &s;
            r.reset();
            try {
                r = std::make_unique<ComponentRunner>(
                    *domain_, config_, *spec, *ComponentRegistry::instance().find(spec->type));
                r->start();
            } catch (const std::exception& e) {
                g_log.error("component '" + name + "' cannot restart: " + e.what());
                exit_code = 1;
                return true;
            }
            continue;
        }
        g_log.error(config_.on_error == ErrorPolicy::kRestart
                        ? "component '" + name + "' failed too often; stopping"
                        : "stopping (on_component_error: stop)");
        exit_code = 1;
        return true;
    }
    return false;
}

int Host::run() {
    using clock = std::chrono::steady_clock;
    for (auto& r : runners_) r->start();
    g_log.info("running " + std::to_string(runners_.size()) + " components on DDS domain " +
               std::to_string(config_.domain_id) + " (configured in " +
               std::to_string(static_cast<int>(startup_ms_)) + " ms)");
    const SystemdNotifier systemd;
    systemd.notify("READY=1\nSTATUS=running " + std::to_string(runners_.size()) + " components");
    Watchdog watchdog(systemd, runners_);
    bool has_sources = false;
    for (const auto& r : runners_) has_sources |= r->is_source();

    sigset_t set;
    sigemptyset(&set);
    sigaddset(&set, SIGINT);
    sigaddset(&set, SIGTERM);
    int exit_code = 0;
    auto idle_since = clock::now();
    std::uint64_t idle_count = 0;
    bool signalled = false;
    // The components' freed memory goes back to the system every 10 s (heap_trim.hpp), and the
    // log says what the memory is made of every minute (after a trim: in use vs. kept free).
    HeapTrimmer heap_trimmer(10.0);
    const auto memory_every = std::chrono::seconds(60);
    auto next_memory_line = clock::now() + memory_every;
    while (true) {
        const timespec wait{0, 50'000'000};
        const int sig = sigtimedwait(&set, nullptr, &wait);
        if (sig == SIGINT || sig == SIGTERM) {
            g_log.info(std::string("received ") + (sig == SIGINT ? "SIGINT" : "SIGTERM") +
                       ", stopping (deadline " + seconds_text(config_.shutdown_timeout_s) + ")");
            signalled = true;
            break;
        }
        watchdog.poll();
        if (heap_trimmer.poll() && clock::now() >= next_memory_line) {
            std::vector<std::pair<std::string, std::vector<HeldPart>>> held;
            for (const auto& r : runners_) held.emplace_back(r->name(), r->held_memory());
            const std::string parts = held_memory_text(held);
            g_log.info("memory: " + heap_stats_text(heap_stats()) +
                       (parts.empty() ? "" : "; " + parts));
            next_memory_line = clock::now() + memory_every;
        }
        if (stop_) break;
        if (handle_failures(exit_code)) break;
        if (has_sources && config_.exit_when_sources_done) {
            bool all_finished = true;
            for (const auto& r : runners_)
                if (r->is_source() && !r->source_finished()) all_finished = false;
            if (all_finished && all_drained()) {
                g_log.info("every source finished and all input is processed; shutting down");
                break;
            }
        }
        if (!has_sources && config_.idle_exit_s > 0) {
            std::uint64_t total = 0;
            bool idle = true;
            for (const auto& r : runners_) {
                total += r->dispatched();
                idle &= r->idle();
            }
            if (!idle || total != idle_count) {
                idle_count = total;
                idle_since = clock::now();
            } else if (clock::now() - idle_since >
                       std::chrono::duration<double>(config_.idle_exit_s)) {
                g_log.info("no input for " + std::to_string(config_.idle_exit_s) +
                           " s; shutting down");
                break;
            }
        }
    }
    systemd.notify("STOPPING=1");
    const bool timed_out = stop_components((signalled || stop_) ? config_.shutdown_timeout_s
                                                                : config_.finish_timeout_s);
    for (auto& r : runners_)
        if (r->failed() && exit_code == 0) exit_code = 1;
    const bool all_saved = report_outputs();
    if (timed_out) {
        g_log.error("stopped with a component still running: what it had not saved is lost");
        // A stuck component thread cannot be joined; leave without running destructors.
        std::fflush(nullptr);
        std::_Exit(3);
    }
    if (!all_saved && exit_code == 0) exit_code = 4;
    if (exit_code == 0)
        g_log.info("stopped cleanly");
    else if (exit_code == 4)
        g_log.error("stopped, but an output could not be saved (above)");
    else
        g_log.error("stopped after a component failure");
    return exit_code;
}

bool Host::stop_components(double budget) {
    using clock = std::chrono::steady_clock;
    const auto start = clock::now();
    const auto deadline =
        start + std::chrono::duration_cast<clock::duration>(std::chrono::duration<double>(budget));
    // Stop in launch-config order (sources first, sinks last): what a component publishes while
    // it shuts down (its last local map, say) still reaches the components listed after it.
    // A long stop says every 5 s what it waits for.
    for (auto& r : runners_) {
        r->request_stop(deadline);
        auto next_note = clock::now() + std::chrono::seconds(5);
        while (!r->wait_done(std::min(next_note, deadline))) {
            const double waited = std::chrono::duration<double>(clock::now() - start).count();
            if (clock::now() >= deadline) {
                g_log.error("component '" + r->name() + "' did not stop within the " +
                            seconds_text(budget) + " deadline (still in " + r->activity() +
                            "; shutdown_timeout_s sets the deadline)");
                // Give the others what is left of a short grace to flush their outputs.
                for (auto& o : runners_) o->request_stop(deadline);
                for (auto& o : runners_)
                    if (o != r) o->wait_done(clock::now() + std::chrono::milliseconds(200));
                return true;
            }
            g_log.info("stopping: waiting for '" + r->name() + "' (" + r->activity() + "), " +
                       seconds_text(waited) + " of " + seconds_text(budget));
            next_note += std::chrono::seconds(5);
        }
    }
    return false;
}

bool Host::report_outputs() const {
    bool all_ok = true;
    for (const auto& r : runners_) {
        for (const auto& o : r->outputs()) {
            const std::string line = o.what + " (" + r->name() + "): " + o.path +
                                     (o.detail.empty() ? "" : " (" + o.detail + ")");
            if (o.ok) {
                g_log.info("saved " + line);
            } else {
                g_log.error("NOT saved: " + line);
                all_ok = false;
            }
        }
    }
    return all_ok;
}

}  // namespace ltm::runtime
