#pragma once
// A component's background thread: a bounded queue of items in, one work function out, for work
// too long for the component's own thread (a localisation, a maintenance pass, a meshing).
//
//   runtime::Worker<Scan> worker_({"maintenance", "work", 50, BusyPolicy::kBlock},
//                                 [this](auto& step, const StopToken& stop) { ... },
//                                 [this](const std::string& what) { report(what); });
//   worker_.start();            // on_activate
//   worker_.push(std::move(scan));
//   worker_.stop();             // on_shutdown: finishes (or abandons) what waits, joins
//
// What a full queue does to a new item is the BusyPolicy: the producer waits for room
// (back-pressure, offline), the oldest item is dropped (live: the newest is processed next), or
// the new item is dropped while the worker is busy. Dropped items are counted (skipped()).
// Besides the queue a worker takes
//  - a latest value (set_latest): only the newest matters; it is handed to the work function with
//    the next item (a new pose graph, an initial pose), or alone when no item waits;
//  - tasks (post): run before the next item, in order, never dropped (requests).
// The work function gets a StopToken: long work looks at it at safe points and ends early when a
// stop abandons the queue (StopPolicy::kAbandon, or stop()'s deadline passed). An exception out of
// the work function is reported to on_error and the worker goes on with the next item.
//
// The thread is named "component/role" (15 characters at most, as Linux allows) so that a
// profiler attributes its CPU time.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <utility>
#include <variant>

namespace ltm::runtime {

// What long work looks at to end early at a safe point.
class StopToken {
  public:
    explicit StopToken(const std::atomic<bool>& flag) : flag_(&flag) {}
    bool stop_requested() const { return flag_->load(std::memory_order_relaxed); }

  private:
    const std::atomic<bool>* flag_;
};

enum class BusyPolicy {
    kBlock,          // the producer waits for room in the queue (back-pressure)
    kDropOldest,     // a full queue drops its oldest item
    kSkipWhileBusy,  // an item that comes while the worker is busy or the queue full is dropped
};

enum class StopPolicy {
    kFinish,   // stop() processes every item, task and latest value still waiting
    kAbandon,  // stop() drops what waits and asks the running work to end early
};

struct WorkerOptions {
    std::string component;  // the thread's name: "component/role", cut to 15 characters
    std::string role = "work";
    std::size_t capacity = 1;  // items waiting for the worker (the one in work not counted)
    BusyPolicy busy = BusyPolicy::kBlock;
    StopPolicy stop = StopPolicy::kFinish;
};

// "component/role" in at most 15 characters: the component's name is cut, the role kept.
std::string worker_thread_name(const std::string& component, const std::string& role);
// A component's own thread (its handlers and timers): the component's name, cut to 15 characters.
// Together with worker_thread_name the scheme is: no '/' = the component's own thread, "c/role" =
// its worker `role` (a profiler's or `./ltm bench budget`'s way back to the component).
std::string component_thread_name(const std::string& component);
// Names the calling thread (best effort: a failure is not an error).
void set_current_thread_name(const std::string& name);

template <class Item, class Latest = std::monostate>
class Worker {
  public:
    // One step of work: the next item (none when only a latest value came) and the latest value,
    // when a new one came since the previous step.
    struct Step {
        std::optional<Item> item;
        std::optional<Latest> latest;
    };
    using Work = std::function<void(Step& step, const StopToken& stop)>;
    using Task = std::function<void(const StopToken& stop)>;
    using OnError = std::function<void(const std::string& what)>;
    using Clock = std::chrono::steady_clock;

    Worker(WorkerOptions options, Work work, OnError on_error)
        : options_(std::move(options)), work_(std::move(work)), on_error_(std::move(on_error)) {
        if (options_.capacity == 0) options_.capacity = 1;
    }
    ~Worker() { stop(); }
    Worker(const Worker&) = delete;
    Worker& operator=(const Worker&) = delete;

    // Starts the thread; `first` (a map to load, say) runs on it before any item.
    void start(Task first = {}) {
        std::lock_guard<std::mutex> lock(mutex_);
        if (thread_.joinable() || stopping_) return;
        running_ = started_ = true;
        thread_ = std::thread([this, first = std::move(first)] { run(first); });
    }

    // Queues an item as the BusyPolicy says; false when it (or nothing: kBlock) was dropped, or
    // the worker is stopping.
    bool push(Item item) {
        return push_merge(std::move(item), [](Item&, Item&) { return false; });
    }

    // As push(), but first offers the item to every waiting one: when merge(waiting, item) returns
    // true it has taken the item's place (a newer revision of the same map) and nothing is queued.
    template <class Merge>
    bool push_merge(Item item, Merge&& merge) {
        std::unique_lock<std::mutex> lock(mutex_);
        if (stopping_) {
            ++abandoned_;
            return false;
        }
        for (Item& waiting : queue_)
            if (merge(waiting, item)) return true;
        switch (options_.busy) {
            case BusyPolicy::kBlock:
                room_cv_.wait(lock, [&] { return queue_.size() < options_.capacity || stopping_; });
                if (stopping_) {
                    ++abandoned_;
                    return false;
                }
                break;
            case BusyPolicy::kDropOldest:
                if (queue_.size() >= options_.capacity) {
                    queue_.pop_front();
                    ++skipped_;
                }
                break;
            case BusyPolicy::kSkipWhileBusy:
                if (busy_ || queue_.size() >= options_.capacity) {
                    ++skipped_;
                    return false;
                }
                break;
        }
        queue_.push_back(std::move(item));
        work_cv_.notify_all();
        return true;
    }

    // Drops the oldest waiting item (counted in skipped()): a producer's own bound on the queue
    // (its items' memory, say) beside the capacity. False when nothing waits.
    bool drop_oldest() {
        std::lock_guard<std::mutex> lock(mutex_);
        if (queue_.empty()) return false;
        queue_.pop_front();
        ++skipped_;
        room_cv_.notify_all();
        return true;
    }

    // Replaces the latest value (never dropped, never waits).
    void set_latest(Latest value) {
        std::lock_guard<std::mutex> lock(mutex_);
        latest_ = std::move(value);
        work_cv_.notify_all();
    }

    // Runs `task` on the worker before the next item (never dropped while the worker runs).
    void post(Task task) {
        std::lock_guard<std::mutex> lock(mutex_);
        if (stopping_) {
            ++abandoned_;
            return;
        }
        tasks_.push_back(std::move(task));
        work_cv_.notify_all();
    }

    // Waits until nothing waits and the worker is not busy (or it stopped, or never started).
    void wait_idle() {
        std::unique_lock<std::mutex> lock(mutex_);
        room_cv_.wait(lock, [&] {
            return !running_ || stopping_ ||
                   (queue_.empty() && tasks_.empty() && !latest_ && !busy_);
        });
    }

    // Asks the running work to end early (the token) and drops what waits.
    void interrupt() {
        std::lock_guard<std::mutex> lock(mutex_);
        abandon_locked();
    }

    // Stops the worker and joins it: with StopPolicy::kFinish it first processes what waits,
    // until `deadline`; then (or at once with kAbandon) the waiting items are dropped and the
    // running work is asked to end early. Idempotent; a worker never started just drops its queue.
    void stop(Clock::time_point deadline = Clock::time_point::max()) {
        std::unique_lock<std::mutex> lock(mutex_);
        stopping_ = true;
        if (options_.stop == StopPolicy::kAbandon || !running_) abandon_locked();
        work_cv_.notify_all();
        room_cv_.notify_all();
        if (running_ && deadline != Clock::time_point::max() &&
            !room_cv_.wait_until(lock, deadline, [&] { return !running_; }))
            abandon_locked();
        lock.unlock();
        if (thread_.joinable() && thread_.get_id() != std::this_thread::get_id()) thread_.join();
    }

    bool started() const {
        std::lock_guard<std::mutex> lock(mutex_);
        return started_;
    }
    std::uint64_t skipped() const {
        std::lock_guard<std::mutex> lock(mutex_);
        return skipped_;
    }
    std::uint64_t abandoned() const {
        std::lock_guard<std::mutex> lock(mutex_);
        return abandoned_;
    }
    std::uint64_t processed() const {
        std::lock_guard<std::mutex> lock(mutex_);
        return processed_;
    }
    std::uint64_t failures() const {
        std::lock_guard<std::mutex> lock(mutex_);
        return failures_;
    }
    bool busy() const {
        std::lock_guard<std::mutex> lock(mutex_);
        return busy_;
    }
    std::size_t waiting() const {
        std::lock_guard<std::mutex> lock(mutex_);
        return queue_.size();
    }

  private:
    void abandon_locked() {
        abandoned_ += queue_.size() + tasks_.size();
        queue_.clear();
        tasks_.clear();
        latest_.reset();
        interrupted_ = true;
        work_cv_.notify_all();
        room_cv_.notify_all();
    }

    template <class Fn>
    void guarded(Fn&& fn) {
        std::string what;
        try {
            fn();
            return;
        } catch (const std::exception& e) {
            what = e.what();
        } catch (...) {
            what = "unknown exception";
        }
        {
            std::lock_guard<std::mutex> lock(mutex_);
            ++failures_;
        }
        if (on_error_) {
            try {
                on_error_(what);
            } catch (...) {
                // A reporter that throws must not end the worker either.
            }
        }
    }

    void run(const Task& first) {
        set_current_thread_name(worker_thread_name(options_.component, options_.role));
        const StopToken token(interrupted_);
        if (first) {
            {
                std::lock_guard<std::mutex> lock(mutex_);
                busy_ = true;
            }
            guarded([&] { first(token); });
            std::lock_guard<std::mutex> lock(mutex_);
            busy_ = false;
        }
        for (;;) {
            Task task;
            Step step;
            {
                std::unique_lock<std::mutex> lock(mutex_);
                work_cv_.wait(lock, [&] {
                    return !tasks_.empty() || !queue_.empty() || latest_.has_value() || stopping_;
                });
                if (tasks_.empty() && queue_.empty() && !latest_) break;  // stopping, all done
                if (!tasks_.empty()) {
                    task = std::move(tasks_.front());
                    tasks_.pop_front();
                } else {
                    if (!queue_.empty()) {
                        step.item = std::move(queue_.front());
                        queue_.pop_front();
                    }
                    step.latest.swap(latest_);
                }
                busy_ = true;
            }
            room_cv_.notify_all();  // room in the queue
            if (task) {
                guarded([&] { task(token); });
            } else {
                guarded([&] { work_(step, token); });
            }
            {
                std::lock_guard<std::mutex> lock(mutex_);
                busy_ = false;
                ++processed_;
            }
            room_cv_.notify_all();  // done: wait_idle() waits for this
        }
        {
            std::lock_guard<std::mutex> lock(mutex_);
            running_ = false;
        }
        room_cv_.notify_all();
    }

    WorkerOptions options_;
    Work work_;
    OnError on_error_;

    mutable std::mutex mutex_;
    std::condition_variable work_cv_;  // the worker waits for something to do
    std::condition_variable room_cv_;  // producers wait for room, idleness or the end
    std::deque<Item> queue_;
    std::deque<Task> tasks_;
    std::optional<Latest> latest_;
    bool started_ = false, running_ = false, stopping_ = false, busy_ = false;
    std::atomic<bool> interrupted_{false};
    std::uint64_t skipped_ = 0, abandoned_ = 0, processed_ = 0, failures_ = 0;
    std::thread thread_;
};

}  // namespace ltm::runtime
