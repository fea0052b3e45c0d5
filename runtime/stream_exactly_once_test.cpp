// A reliable keep-all (`stream`) topic delivers each sample exactly once, also when a write times
// out on back-pressure and is retried: one writer, a fast reader and a slow one, a blocking time
// of 1 ms and a reader queue of one sample, so that most writes time out on the slow reader after
// the fast one already took the sample.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <map>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "runtime/component.hpp"
#include "runtime/host.hpp"
#include "runtime/launch_config.hpp"

namespace ltm::runtime {
namespace {

std::mutex g_mutex;
std::map<std::string, std::vector<int>> g_received;  // reader name -> indices in arrival order
std::uint64_t g_retried = 0;                         // writes the source repeated after a timeout

// Publishes `count` PoseStamped samples numbered 0.. in header.stamp.sec once `readers` are
// matched, then finishes.
class NumberSource : public Component {
  public:
    explicit NumberSource(ComponentContext& ctx) : ctx_(ctx) {
        count_ = ctx.params().get<int>("count", 40);
        readers_ = ctx.params().get<int>("readers", 2);
        out_ = ctx.advertise<msg::PoseStamped>("numbers", TopicRole::kStream);
        ctx.declare_source();
        ctx.add_timer(0.0, [this] { produce(); });
    }

  private:
    void produce() {
        if (out_.matched() < static_cast<std::uint32_t>(readers_)) {
            ctx_.sleep_until(std::chrono::steady_clock::now() + std::chrono::milliseconds(5));
            return;
        }
        for (int i = 0; i < count_; ++i) {
            msg::PoseStamped m{};
            char frame[] = "test";
            m.header.frame_id = frame;
            m.header.stamp.sec = i;
            ASSERT_TRUE(out_.publish(m));
        }
        {
            std::lock_guard<std::mutex> lock(g_mutex);
            g_retried = out_.retried();
        }
        ctx_.finished();
    }

    ComponentContext& ctx_;
    Publisher<msg::PoseStamped> out_;
    int count_ = 0, readers_ = 0;
};

// Records each sample's number; sleeps `sleep_ms` a sample (a slow reader).
class NumberCounter : public Component {
  public:
    explicit NumberCounter(ComponentContext& ctx) {
        const std::string name = ctx.name();
        const double sleep_ms = ctx.params().get<double>("sleep_ms", 0.0);
        ctx.subscribe<msg::PoseStamped>(
            "numbers", TopicRole::kStream, [name, sleep_ms](const msg::PoseStamped& m) {
                {
                    std::lock_guard<std::mutex> lock(g_mutex);
                    g_received[name].push_back(m.header.stamp.sec);
                }
                std::this_thread::sleep_for(std::chrono::duration<double, std::milli>(sleep_ms));
            });
    }
};

LTM_REGISTER_COMPONENT(NumberSource, "test_number_source", "numbered samples (test)")
LTM_REGISTER_COMPONENT(NumberCounter, "test_number_counter", "records sample numbers (test)")

TEST(StreamTopic, EverySampleIsDeliveredExactlyOnceWhenWritesTimeOut) {
    const int count = 40;
    const std::string path =
        ::testing::TempDir() + "/exactly_once_" + std::to_string(::getpid()) + ".yaml";
    {
        std::ofstream f(path);
        // A private topic name and loopback only: parallel tests do not meet.
        f << "dds: {interfaces: [lo], multicast: false, peers: [127.0.0.1]}\n"
          << "topics:\n"
          << "  numbers_" << ::getpid() << ": {role: stream, max_blocking_s: 0.001, depth: 1}\n"
          << "components:\n"
          << "  - {name: source, type: test_number_source, params: {count: " << count
          << ", readers: 2}, remap: {numbers: numbers_" << ::getpid() << "}}\n"
          << "  - {name: fast, type: test_number_counter, remap: {numbers: numbers_" << ::getpid()
          << "}}\n"
          << "  - {name: slow, type: test_number_counter, params: {sleep_ms: 15}, remap: "
             "{numbers: numbers_"
          << ::getpid() << "}}\n";
    }
    Host host(load_launch_config(path));
    ASSERT_EQ(host.run(), 0);
    std::lock_guard<std::mutex> lock(g_mutex);
    // The case this test is about happened: writes timed out on the slow reader and were retried.
    EXPECT_GT(g_retried, 0u);
    for (const char* reader : {"fast", "slow"}) {
        const auto& got = g_received[reader];
        std::vector<int> expected(count);
        for (int i = 0; i < count; ++i) expected[i] = i;
        EXPECT_EQ(got, expected) << reader << " did not get every sample exactly once, in order";
    }
    std::remove(path.c_str());
}

}  // namespace
}  // namespace ltm::runtime
