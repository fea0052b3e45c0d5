#pragma once
// One component's execution context: its own thread, a waitset over its readers (the readers'
// histories are its input queues), its timers and its lifecycle.
#include <dds/dds.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "runtime/component.hpp"

namespace ltm::runtime {

class ComponentRunner {
  public:
    // Configures the component (runs its constructor). Throws ConfigError for bad parameters,
    // unknown remaps or a constructor that refused.
    ComponentRunner(Domain& domain, const LaunchConfig& config, const ComponentSpec& spec,
                    const ComponentInfo& info);
    ~ComponentRunner();
    ComponentRunner(const ComponentRunner&) = delete;
    ComponentRunner& operator=(const ComponentRunner&) = delete;

    void start();  // activate: the thread starts and calls on_activate
    // Deactivate + shutdown follow on the component's thread; `deadline`: the host's stop
    // deadline (ComponentContext::work_deadline derives the components' from it).
    void request_stop(std::chrono::steady_clock::time_point deadline =
                          std::chrono::steady_clock::time_point::max());
    // Waits until the thread has run on_shutdown and ended; false when the deadline passed.
    bool wait_done(std::chrono::steady_clock::time_point deadline);

    const std::string& name() const { return spec_.name; }
    const std::string& type() const { return spec_.type; }
    bool failed() const { return failed_; }
    std::string failure() const;
    bool is_source() const { return ctx_->is_source(); }
    bool source_finished() const { return ctx_->is_finished(); }
    // True when the thread is waiting for input and no input is queued.
    bool idle() const;
    std::uint64_t dispatched() const { return dispatched_; }
    // True unless the thread has been inside one handler, timer or lifecycle step for longer
    // than `limit` (the watchdog's test of progress; waiting for input is progress).
    bool making_progress(std::chrono::steady_clock::duration limit) const;
    // The outputs the component reported (ComponentContext::report_output).
    std::vector<ComponentContext::Output> outputs() const { return ctx_->outputs(); }
    // What the component said it holds (ComponentContext::report_memory).
    std::vector<HeldPart> held_memory() const { return ctx_->held_memory(); }
    // What it is doing now, for a stop that takes long: "on_shutdown", "a handler of TOPIC", ...
    std::string activity() const;

  private:
    void run();
    bool dispatch_one_round();  // takes at most one sample from each reader; true when any
    void fail(const std::string& where, const std::string& what);

    ComponentSpec spec_;
    std::unique_ptr<ComponentContext> ctx_;
    std::unique_ptr<Component> component_;
    dds_entity_t waitset_ = 0, guard_ = 0;
    std::thread thread_;
    std::atomic<bool> started_{false}, done_{false}, failed_{false}, waiting_{false};
    std::atomic<std::uint64_t> dispatched_{0};
    // steady_clock ticks when the current step began (0: waiting); the step's name.
    std::atomic<std::int64_t> busy_since_{0};
    // A literal, or the topic of the handler running (its string lives as long as the runner).
    std::atomic<const char*> activity_{"starting"};
    std::atomic<bool> in_handler_{false};
    void begin(const char* activity, bool handler = false);
    void end() { busy_since_ = 0; }
    mutable std::mutex mutex_;
    std::condition_variable done_cv_;
    std::string failure_;
};

}  // namespace ltm::runtime
