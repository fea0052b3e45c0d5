#include "runtime/worker.hpp"

#include <gtest/gtest.h>
#include <pthread.h>

#include <future>
#include <mutex>
#include <vector>

namespace ltm::runtime {
namespace {

using IntWorker = Worker<int>;

// A work function that holds each item until the test opens the gate.
struct Gate {
    std::mutex mutex;
    std::condition_variable cv;
    bool open = false;
    int entered = 0;
    void wait() {
        std::unique_lock<std::mutex> lock(mutex);
        ++entered;
        cv.notify_all();
        cv.wait(lock, [&] { return open; });
    }
    void wait_entered(int n) {
        std::unique_lock<std::mutex> lock(mutex);
        cv.wait(lock, [&] { return entered >= n; });
    }
    void release() {
        std::lock_guard<std::mutex> lock(mutex);
        open = true;
        cv.notify_all();
    }
};

WorkerOptions options(std::size_t capacity, BusyPolicy busy,
                      StopPolicy stop = StopPolicy::kFinish) {
    return WorkerOptions{"test", "work", capacity, busy, stop};
}

TEST(WorkerTest, ThreadNameKeepsTheRoleWithinFifteenCharacters) {
    EXPECT_EQ(worker_thread_name("mesh", "work"), "mesh/work");
    EXPECT_EQ(worker_thread_name("localisation_robot", "work"), "localisati/work");
    EXPECT_LE(worker_thread_name("a", "a_very_long_role_name").size(), 15u);
}

TEST(WorkerTest, ProcessesEveryItemInOrderAndNamesItsThread) {
    std::vector<int> seen;
    std::string name;
    IntWorker w(options(4, BusyPolicy::kBlock),
                [&](IntWorker::Step& s, const StopToken&) {
                    char buf[16] = {};
                    pthread_getname_np(pthread_self(), buf, sizeof buf);
                    name = buf;
                    seen.push_back(*s.item);
                },
                {});
    w.start();
    for (int i = 0; i < 100; ++i) EXPECT_TRUE(w.push(i));
    w.stop();
    ASSERT_EQ(seen.size(), 100u);
    for (int i = 0; i < 100; ++i) EXPECT_EQ(seen[i], i);
    EXPECT_EQ(name, "test/work");
    EXPECT_EQ(w.skipped(), 0u);
}

TEST(WorkerTest, BlockWaitsForRoomAndNeverDrops) {
    Gate gate;
    IntWorker w(options(2, BusyPolicy::kBlock),
                [&](IntWorker::Step&, const StopToken&) { gate.wait(); }, {});
    w.start();
    w.push(0);
    gate.wait_entered(1);  // 0 in work
    w.push(1);
    w.push(2);  // the queue is full now
    EXPECT_EQ(w.waiting(), 2u);
    auto blocked = std::async(std::launch::async, [&] { return w.push(3); });
    EXPECT_EQ(blocked.wait_for(std::chrono::milliseconds(50)), std::future_status::timeout);
    gate.release();
    EXPECT_TRUE(blocked.get());
    w.stop();
    EXPECT_EQ(w.processed(), 4u);
    EXPECT_EQ(w.skipped(), 0u);
}

TEST(WorkerTest, DropOldestKeepsTheNewest) {
    Gate gate;
    std::vector<int> seen;
    IntWorker w(options(2, BusyPolicy::kDropOldest),
                [&](IntWorker::Step& s, const StopToken&) {
                    gate.wait();
                    seen.push_back(*s.item);
                },
                {});
    w.start();
    w.push(0);
    gate.wait_entered(1);
    for (int i = 1; i <= 5; ++i) EXPECT_TRUE(w.push(i));
    EXPECT_EQ(w.waiting(), 2u);
    EXPECT_EQ(w.skipped(), 3u);
    gate.release();
    w.stop();
    EXPECT_EQ(seen, (std::vector<int>{0, 4, 5}));
}

TEST(WorkerTest, DropOldestOnRequestCountsItAsSkipped) {
    // A producer's own bound (bytes, say): it drops the oldest waiting item itself.
    Gate gate;
    std::vector<int> seen;
    IntWorker w(options(10, BusyPolicy::kBlock),
                [&](IntWorker::Step& s, const StopToken&) {
                    gate.wait();
                    seen.push_back(*s.item);
                },
                {});
    EXPECT_FALSE(w.drop_oldest());  // nothing waits
    w.start();
    w.push(0);
    gate.wait_entered(1);  // 0 in work
    for (int i = 1; i <= 3; ++i) w.push(i);
    EXPECT_TRUE(w.drop_oldest());
    EXPECT_EQ(w.waiting(), 2u);
    EXPECT_EQ(w.skipped(), 1u);
    gate.release();
    w.stop();
    EXPECT_EQ(seen, (std::vector<int>{0, 2, 3}));
}

TEST(WorkerTest, SkipWhileBusyDropsTheNewItem) {
    Gate gate;
    std::vector<int> seen;
    IntWorker w(options(1, BusyPolicy::kSkipWhileBusy),
                [&](IntWorker::Step& s, const StopToken&) {
                    gate.wait();
                    seen.push_back(*s.item);
                },
                {});
    w.start();
    EXPECT_TRUE(w.push(0));
    gate.wait_entered(1);
    EXPECT_FALSE(w.push(1));
    EXPECT_FALSE(w.push(2));
    EXPECT_EQ(w.skipped(), 2u);
    gate.release();
    w.wait_idle();
    EXPECT_TRUE(w.push(3));
    w.stop();
    EXPECT_EQ(seen, (std::vector<int>{0, 3}));
}

TEST(WorkerTest, StopFinishesQueuedItems) {
    Gate gate;
    int done = 0;
    IntWorker w(options(10, BusyPolicy::kBlock),
                [&](IntWorker::Step&, const StopToken&) {
                    gate.wait();
                    ++done;
                },
                {});
    w.start();
    for (int i = 0; i < 5; ++i) w.push(i);
    gate.wait_entered(1);
    auto stopped = std::async(std::launch::async, [&] { w.stop(); });
    gate.release();
    stopped.get();
    EXPECT_EQ(done, 5);
    EXPECT_EQ(w.abandoned(), 0u);
    EXPECT_FALSE(w.push(6));  // stopped: refused
}

TEST(WorkerTest, StopAbandonsQueuedItemsAndInterruptsTheRunningOne) {
    std::atomic<bool> saw_stop{false};
    std::atomic<bool> entered{false};
    int done = 0;
    IntWorker w(options(10, BusyPolicy::kBlock, StopPolicy::kAbandon),
                [&](IntWorker::Step&, const StopToken& stop) {
                    entered = true;
                    while (!stop.stop_requested()) std::this_thread::yield();  // a long pass
                    saw_stop = true;
                    ++done;
                },
                {});
    w.start();
    for (int i = 0; i < 5; ++i) w.push(i);
    while (!entered) std::this_thread::yield();
    w.stop();
    EXPECT_TRUE(saw_stop);
    EXPECT_EQ(done, 1);
    EXPECT_EQ(w.abandoned(), 4u);
}

TEST(WorkerTest, StopDeadlineInterruptsLongWork) {
    std::atomic<bool> entered{false};
    std::vector<int> seen;
    IntWorker w(options(10, BusyPolicy::kBlock),
                [&](IntWorker::Step& s, const StopToken& stop) {
                    entered = true;
                    while (!stop.stop_requested()) std::this_thread::yield();
                    seen.push_back(*s.item);
                },
                {});
    w.start();
    for (int i = 0; i < 3; ++i) w.push(i);
    while (!entered) std::this_thread::yield();
    w.stop(std::chrono::steady_clock::now() + std::chrono::milliseconds(20));
    EXPECT_EQ(seen, (std::vector<int>{0}));  // ended early; 1 and 2 abandoned
    EXPECT_EQ(w.abandoned(), 2u);
}

TEST(WorkerTest, ExceptionsAreReportedAndTheWorkerGoesOn) {
    std::vector<std::string> errors;
    std::vector<int> seen;
    IntWorker w(
        options(10, BusyPolicy::kBlock),
        [&](IntWorker::Step& s, const StopToken&) {
            if (*s.item == 1) throw std::runtime_error("bad item");
            if (*s.item == 2) throw 42;
            seen.push_back(*s.item);
        },
        [&](const std::string& what) { errors.push_back(what); });
    w.start();
    for (int i = 0; i < 4; ++i) w.push(i);
    w.stop();
    EXPECT_EQ(seen, (std::vector<int>{0, 3}));
    EXPECT_EQ(errors, (std::vector<std::string>{"bad item", "unknown exception"}));
    EXPECT_EQ(w.failures(), 2u);
}

TEST(WorkerTest, LatestValueComesWithTheNextItemOrAlone) {
    Gate gate;
    using W = Worker<int, std::string>;
    std::vector<std::pair<int, std::string>> seen;
    W w(options(10, BusyPolicy::kBlock),
        [&](W::Step& s, const StopToken&) {
            if (s.item && *s.item == 0) gate.wait();
            seen.emplace_back(s.item.value_or(-1), s.latest.value_or(""));
        },
        {});
    w.start();
    w.push(0);
    gate.wait_entered(1);
    w.set_latest("a");
    w.set_latest("b");  // only the newest matters
    w.push(1);
    gate.release();
    w.wait_idle();
    w.set_latest("c");
    w.stop();
    EXPECT_EQ(seen, (std::vector<std::pair<int, std::string>>{{0, ""}, {1, "b"}, {-1, "c"}}));
}

TEST(WorkerTest, TasksGoFirstAndMergedItemsTakeTheirPlace) {
    Gate gate;
    std::vector<std::string> seen;
    IntWorker w(options(10, BusyPolicy::kBlock),
                [&](IntWorker::Step& s, const StopToken&) {
                    if (*s.item == 0) gate.wait();
                    seen.push_back(std::to_string(*s.item));
                },
                {});
    w.start([&](const StopToken&) { seen.push_back("first"); });
    w.push(0);
    gate.wait_entered(1);
    w.push(10);
    w.push(20);
    // 11 takes the place of 10 (same tens).
    EXPECT_TRUE(w.push_merge(11, [](int& waiting, int& item) {
        if (waiting / 10 != item / 10) return false;
        waiting = item;
        return true;
    }));
    w.post([&](const StopToken&) { seen.push_back("task1"); });
    w.post([&](const StopToken&) { seen.push_back("task2"); });
    gate.release();
    w.stop();
    EXPECT_EQ(seen, (std::vector<std::string>{"first", "0", "task1", "task2", "11", "20"}));
}

TEST(WorkerTest, WaitIdleReturnsWhenEverythingIsDone) {
    std::atomic<int> done{0};
    IntWorker w(options(1, BusyPolicy::kBlock),
                [&](IntWorker::Step&, const StopToken&) {
                    std::this_thread::sleep_for(std::chrono::milliseconds(2));
                    ++done;
                },
                {});
    w.start();
    for (int i = 0; i < 5; ++i) w.push(i);
    w.wait_idle();
    EXPECT_EQ(done.load(), 5);
    w.stop();
}

TEST(WorkerTest, StopWithoutStartDropsTheQueue) {
    IntWorker w(options(4, BusyPolicy::kDropOldest), [](IntWorker::Step&, const StopToken&) {}, {});
    w.push(1);
    w.push(2);
    w.stop();
    EXPECT_EQ(w.abandoned(), 2u);
    EXPECT_EQ(w.processed(), 0u);
}

}  // namespace
}  // namespace ltm::runtime
