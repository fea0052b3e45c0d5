#include "runtime/host.hpp"

#include <malloc.h>
#include <signal.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>

#include "runtime/logging.hpp"

namespace ltm::runtime {
namespace {

Logger g_log("host");

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
    while (true) {
        const timespec wait{0, 50'000'000};
        const int sig = sigtimedwait(&set, nullptr, &wait);
        if (sig == SIGINT || sig == SIGTERM) {
            g_log.info(std::string("received ") + (sig == SIGINT ? "SIGINT" : "SIGTERM") +
                       ", shutting down");
            signalled = true;
            break;
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

    // A signal asks for a quick stop; a finished run may take longer for final saves.
    const double budget =
        (signalled || stop_) ? config_.shutdown_timeout_s : config_.finish_timeout_s;
    const auto deadline = clock::now() + std::chrono::duration_cast<clock::duration>(
                                             std::chrono::duration<double>(budget));
    // Stop in launch-config order (sources first, sinks last): what a component publishes while
    // it shuts down (its last local map, say) still reaches the components listed after it.
    bool timed_out = false;
    for (auto& r : runners_) {
        r->request_stop();
        if (!r->wait_done(deadline)) {
            g_log.error("component '" + r->name() + "' did not stop within " +
                        std::to_string(budget) + " s");
            timed_out = true;
            break;
        }
    }
    if (timed_out) {
        // Give the others what is left of a short grace to flush their outputs.
        for (auto& r : runners_) r->request_stop();
        for (auto& r : runners_)
            r->wait_done(std::max(deadline, clock::now()) + std::chrono::milliseconds(200));
    }
    if (timed_out) {
        // A stuck component thread cannot be joined; leave without running destructors.
        std::fflush(nullptr);
        std::_Exit(3);
    }
    for (auto& r : runners_)
        if (r->failed() && exit_code == 0) exit_code = 1;
    g_log.info(exit_code == 0 ? "stopped cleanly" : "stopped after a component failure");
    return exit_code;
}

}  // namespace ltm::runtime
