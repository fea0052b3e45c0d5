// Latency probes for `./ltm bench dds`: a source of synthetic PointCloud2 scans stamped with
// CLOCK_MONOTONIC (comparable across processes on one machine) and a sink measuring the delay.
#include <time.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <vector>

#include "runtime/component.hpp"
#include "runtime/convert/geometry.hpp"
#include "runtime/convert/pointcloud2.hpp"

namespace ltm::bench {
namespace {

using runtime::TopicRole;

double monotonic_s() {
    timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

// Publishes `count` clouds of `points` points at `rate_hz`, header stamp = CLOCK_MONOTONIC.
class LatencySource : public runtime::Component {
  public:
    explicit LatencySource(runtime::ComponentContext& ctx) : ctx_(ctx) {
        auto& p = ctx.params();
        const int points = p.get<int>("points", 120000);
        count_ = p.get<int>("count", 200);
        const double rate = p.get<double>("rate_hz", 10.0);
        wait_for_readers_ = p.get<int>("wait_for_readers", 1);
        if (points < 1 || count_ < 1 || rate <= 0)
            p.fail("points", "points, count and rate_hz must be positive");
        std::mt19937 rng(7);
        std::uniform_real_distribution<float> u(-50.f, 50.f);
        for (int i = 0; i < points; ++i) {
            cloud_.points.emplace_back(u(rng), u(rng), u(rng) * 0.1f);
            cloud_.intensity.push_back(0.5f);
        }
        out_ = ctx.advertise<msg::PointCloud2>("points", TopicRole::kSensor);
        ctx.declare_source();
        ctx.add_timer(1.0 / rate, [this] { tick(); });
    }

  private:
    void tick() {
        if (sent_ >= count_) return;
        if (static_cast<int>(out_.matched()) < wait_for_readers_) return;
        cloud_.stamp = monotonic_s();
        out_.publish(builder_.build(cloud_));
        if (++sent_ == count_) ctx_.finished();
    }

    runtime::ComponentContext& ctx_;
    common::PointCloud cloud_;
    convert::PointCloud2Builder builder_;
    runtime::Publisher<msg::PointCloud2> out_;
    int count_ = 0, sent_ = 0, wait_for_readers_ = 1;
};

// Measures now - header.stamp for every cloud; prints median/p99 and writes them to `report`.
class LatencySink : public runtime::Component {
  public:
    explicit LatencySink(runtime::ComponentContext& ctx) : ctx_(ctx) {
        report_ = ctx.params().get<std::string>("report", "");
        decode_ = ctx.params().get<bool>("decode", true);
        ctx.subscribe<msg::PointCloud2>(
            "points", TopicRole::kSensor, [this](const msg::PointCloud2& m) {
                if (decode_) {
                    common::PointCloud c;
                    convert::from_pointcloud2(m, c);
                }
                latencies_ms_.push_back((monotonic_s() - convert::to_seconds(m.header.stamp)) *
                                        1e3);
            });
    }

    void on_shutdown() override {
        if (latencies_ms_.empty()) {
            ctx_.log().warn("no samples received");
            return;
        }
        std::vector<double> v = latencies_ms_;
        std::sort(v.begin(), v.end());
        auto pct = [&](double q) {
            return v[std::min(v.size() - 1, static_cast<std::size_t>(q * (v.size() - 1) + 0.5))];
        };
        char line[200];
        std::snprintf(line, sizeof line, "samples %zu median_ms %.3f p99_ms %.3f max_ms %.3f",
                      v.size(), pct(0.5), pct(0.99), v.back());
        ctx_.log().info(line);
        if (!report_.empty()) std::ofstream(report_) << line << "\n";
    }

  private:
    runtime::ComponentContext& ctx_;
    std::string report_;
    bool decode_ = true;
    std::vector<double> latencies_ms_;
};

}  // namespace
}  // namespace ltm::bench

LTM_REGISTER_COMPONENT(ltm::bench::LatencySource, "bench_latency_source",
                       "benchmark: synthetic PointCloud2 scans stamped with CLOCK_MONOTONIC")
LTM_REGISTER_COMPONENT(ltm::bench::LatencySink, "bench_latency_sink",
                       "benchmark: measures the delay of received PointCloud2 scans")
