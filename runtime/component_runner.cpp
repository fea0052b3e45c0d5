#include "runtime/component_runner.hpp"

#include <exception>

#include "runtime/dds_error.hpp"
#include "runtime/raw_cdr.hpp"
#include "runtime/worker.hpp"

namespace ltm::runtime {
namespace {

// Returns a loan on every exit path, also when a handler throws.
struct Loan {
    dds_entity_t reader;
    void* buf[1] = {nullptr};
    int n = 0;
    ~Loan() {
        if (n > 0) dds_return_loan(reader, buf, n);
    }
};

}  // namespace

ComponentRunner::ComponentRunner(Domain& domain, const LaunchConfig& config,
                                 const ComponentSpec& spec, const ComponentInfo& info)
    : spec_(spec) {
    ctx_ = std::make_unique<ComponentContext>(domain, config, spec_);
    try {
        component_ = info.make(*ctx_);
    } catch (const ConfigError&) {
        throw;
    } catch (const std::exception& e) {
        throw ConfigError(config.file, spec.line, spec.name,
                          std::string("cannot configure: ") + e.what());
    }
    ctx_->params().check_all_used();
    ctx_->check_remaps_used();
    waitset_ = check_dds(dds_create_waitset(domain.participant()), "creating a waitset");
    guard_ =
        check_dds(dds_create_guardcondition(domain.participant()), "creating a guard condition");
    check_dds(dds_waitset_attach(waitset_, guard_, 0), "attaching the guard condition");
    ctx_->attach_waitset(waitset_);
}

ComponentRunner::~ComponentRunner() {
    if (thread_.joinable()) {
        request_stop();
        thread_.join();
    }
    component_.reset();
    ctx_.reset();
    if (waitset_ > 0) dds_delete(waitset_);
    if (guard_ > 0) dds_delete(guard_);
}

void ComponentRunner::start() {
    started_ = true;
    thread_ = std::thread([this] { run(); });
}

void ComponentRunner::request_stop(std::chrono::steady_clock::time_point deadline) {
    ctx_->request_stop(deadline);
    dds_set_guardcondition(guard_, true);
}

bool ComponentRunner::wait_done(std::chrono::steady_clock::time_point deadline) {
    if (!started_) return true;
    std::unique_lock<std::mutex> lock(mutex_);
    if (!done_cv_.wait_until(lock, deadline, [this] { return done_.load(); })) return false;
    lock.unlock();
    if (thread_.joinable()) thread_.join();
    return true;
}

std::string ComponentRunner::failure() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return failure_;
}

bool ComponentRunner::idle() const {
    if (done_) return true;
    if (!waiting_) return false;
    for (const auto& s : ctx_->subscriptions())
        if (dds_triggered(s.readcond) > 0) return false;
    return true;
}

void ComponentRunner::begin(const char* activity, bool handler) {
    activity_ = activity;
    in_handler_ = handler;
    busy_since_ = std::chrono::steady_clock::now().time_since_epoch().count();
}

bool ComponentRunner::making_progress(std::chrono::steady_clock::duration limit) const {
    if (done_ || !started_) return true;
    const std::int64_t since = busy_since_;
    if (since == 0) return true;
    return std::chrono::steady_clock::now().time_since_epoch().count() - since < limit.count();
}

std::string ComponentRunner::activity() const {
    if (done_) return "done";
    if (busy_since_ == 0) return "waiting for input";
    const std::string a = activity_.load();
    return in_handler_ ? "its handler of " + a : a;
}

void ComponentRunner::fail(const std::string& where, const std::string& what) {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        failure_ =
            "component '" + spec_.name + "' (" + spec_.type + ") threw in " + where + ": " + what;
    }
    ctx_->log().error(failure());
    failed_ = true;
}

bool ComponentRunner::dispatch_one_round() {
    bool any = false;
    auto& subs = ctx_->subscriptions();
    // By index: a handler may add subscriptions (the deque keeps `s` valid).
    for (std::size_t i = 0; i < subs.size(); ++i) {
        auto& s = subs[i];
        try {
            if (s.raw_handler) {
                dds_sample_info_t info;
                if (take_cdr(s.reader, s.buffer, info) <= 0) continue;
                any = true;
                if (!info.valid_data || s.duplicate(info)) continue;
                begin(s.topic.c_str(), true);
                s.raw_handler(s.buffer, info);
                end();
            } else {
                Loan loan{s.reader};
                dds_sample_info_t info;
                loan.n = dds_take(s.reader, loan.buf, &info, 1, 1);
                if (loan.n <= 0) continue;
                any = true;
                if (!info.valid_data || s.duplicate(info)) continue;
                begin(s.topic.c_str(), true);
                s.handler(loan.buf[0]);
                end();
            }
        } catch (const std::exception& e) {
            end();
            fail("its handler of " + s.topic, e.what());
            return any;
        } catch (...) {
            end();
            fail("its handler of " + s.topic, "unknown exception");
            return any;
        }
        ++dispatched_;
    }
    return any;
}

void ComponentRunner::run() {
    using clock = std::chrono::steady_clock;
    set_current_thread_name(component_thread_name(spec_.name));
    auto lifecycle = [this](const char* stage, void (Component::*hook)()) {
        begin(stage);
        try {
            (component_.get()->*hook)();
            end();
            return true;
        } catch (const std::exception& e) {
            end();
            fail(stage, e.what());
        } catch (...) {
            end();
            fail(stage, "unknown exception");
        }
        return false;
    };

    bool ok = lifecycle("on_activate", &Component::on_activate);
    while (ok && !ctx_->stop_requested() && !failed_) {
        // 1. Input: round-robin over the readers, a bounded number of rounds so timers still run.
        bool input = false;
        for (int round = 0; round < 64 && !ctx_->stop_requested() && !failed_; ++round) {
            if (!dispatch_one_round()) break;
            input = true;
        }
        if (failed_) break;
        // 2. Timers.
        auto now = clock::now();
        auto next = clock::time_point::max();
        bool looping = false;
        for (auto& t : ctx_->timers()) {
            if (ctx_->stop_requested() || failed_) break;
            try {
                if (t.period_s == 0) {
                    if (ctx_->is_finished()) continue;
                    looping = true;
                    if (!input) {
                        begin("a timer");
                        t.fn();
                        end();
                    }
                    continue;
                }
                if (now >= t.next) {
                    begin("a timer");
                    t.fn();
                    end();
                    const auto period = std::chrono::duration_cast<clock::duration>(
                        std::chrono::duration<double>(t.period_s));
                    t.next += period;
                    now = clock::now();
                    if (t.next < now) t.next = now + period;  // fell behind: do not burst
                }
                next = std::min(next, t.next);
            } catch (const std::exception& e) {
                end();
                fail("a timer", e.what());
            } catch (...) {
                end();
                fail("a timer", "unknown exception");
            }
        }
        if (failed_ || ctx_->stop_requested()) break;
        // 3. Wait for input, a timer or a stop.
        dds_duration_t timeout = DDS_INFINITY;
        if (input || looping) {
            timeout = 0;
        } else if (next != clock::time_point::max()) {
            timeout = std::max<dds_duration_t>(
                0,
                std::chrono::duration_cast<std::chrono::nanoseconds>(next - clock::now()).count());
        }
        if (timeout != 0) {
            waiting_ = true;
            dds_waitset_wait(waitset_, nullptr, 0, timeout);
            waiting_ = false;
        }
        bool triggered = false;
        dds_take_guardcondition(guard_, &triggered);
    }
    // Input already queued when the stop came is still processed (bounded), so that the last
    // outputs of the components stopped before this one are not lost.
    if (ok && !failed_) {
        const auto drain_until = clock::now() + std::chrono::milliseconds(500);
        while (clock::now() < drain_until && !failed_ && dispatch_one_round()) {
        }
    }
    lifecycle("on_deactivate", &Component::on_deactivate);
    lifecycle("on_shutdown", &Component::on_shutdown);
    {
        std::lock_guard<std::mutex> lock(mutex_);
        done_ = true;
    }
    done_cv_.notify_all();
}

}  // namespace ltm::runtime
