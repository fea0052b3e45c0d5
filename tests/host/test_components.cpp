// Components that only the test host links: fault injection and malformed input.
#include <chrono>
#include <fstream>
#include <stdexcept>
#include <thread>

#include "runtime/component.hpp"

namespace ltm::tests {
namespace {

using runtime::TopicRole;

// Counts scans on `points`; throws at the `throw_at`-th (1-based) one, or in on_activate.
class Faulty : public runtime::Component {
  public:
    explicit Faulty(runtime::ComponentContext& ctx) {
        throw_at_ = ctx.params().get<int>("throw_at", 1);
        if (ctx.params().get<bool>("throw_in_activate", false)) throw_at_ = 0;
        ctx.subscribe<msg::PointCloud2>("points", TopicRole::kSensor,
                                        [this](const msg::PointCloud2&) {
                                            if (++count_ == throw_at_)
                                                throw std::runtime_error("injected fault");
                                        });
    }
    void on_activate() override {
        if (throw_at_ == 0) throw std::runtime_error("injected fault in activate");
    }

  private:
    int throw_at_ = 1, count_ = 0;
};

// Blocks in on_shutdown for `seconds`: the host must not wait for it forever.
class Stuck : public runtime::Component {
  public:
    explicit Stuck(runtime::ComponentContext& ctx) {
        seconds_ = ctx.params().get<double>("seconds", 30.0);
    }
    void on_shutdown() override {
        std::this_thread::sleep_for(std::chrono::duration<double>(seconds_));
    }

  private:
    double seconds_;
};

// Publishes one PointCloud2 whose x y z are float64, then finishes.
class BadCloudSource : public runtime::Component {
  public:
    explicit BadCloudSource(runtime::ComponentContext& ctx) : ctx_(ctx) {
        out_ = ctx.advertise<msg::PointCloud2>("points", TopicRole::kStream);
        ctx.declare_source();
        ctx.add_timer(0.0, [this] {
            if (out_.matched() < 1) {
                ctx_.sleep_until(std::chrono::steady_clock::now() + std::chrono::milliseconds(5));
                return;
            }
            char x[] = "x", y[] = "y", z[] = "z", frame[] = "lidar";
            msg::PointField fields[3] = {{x, 0, 8, 1}, {y, 8, 8, 1}, {z, 16, 8, 1}};
            double data[6] = {1, 2, 3, 4, 5, 6};
            msg::PointCloud2 m{};
            m.header.frame_id = frame;
            m.height = 1;
            m.width = 2;
            m.fields._buffer = fields;
            m.fields._length = m.fields._maximum = 3;
            m.point_step = 24;
            m.row_step = 48;
            m.data._buffer = reinterpret_cast<std::uint8_t*>(data);
            m.data._length = m.data._maximum = sizeof data;
            out_.publish(m);
            ctx_.finished();
        });
    }

  private:
    runtime::ComponentContext& ctx_;
    runtime::Publisher<msg::PointCloud2> out_;
};

// Writes `file` in on_shutdown (after `seconds` of work, a stop point every 10 ms) and reports it
// as an output: saved, or not (a file in a folder that does not exist).
class SlowSaver : public runtime::Component {
  public:
    explicit SlowSaver(runtime::ComponentContext& ctx) : ctx_(ctx) {
        file_ = ctx.params().get<std::string>("file", "");
        seconds_ = ctx.params().get<double>("seconds", 0.0);
    }
    void on_shutdown() override {
        std::this_thread::sleep_for(std::chrono::duration<double>(seconds_));
        std::ofstream out(file_);
        out << "saved\n";
        out.close();
        ctx_.report_output("test file", file_, bool(out), out ? "1 line" : "cannot write");
    }

  private:
    runtime::ComponentContext& ctx_;
    std::string file_;
    double seconds_ = 0;
};

}  // namespace
}  // namespace ltm::tests

LTM_REGISTER_COMPONENT(ltm::tests::Faulty, "test_faulty", "test: throws on its n-th input scan")
LTM_REGISTER_COMPONENT(ltm::tests::SlowSaver, "test_slow_saver",
                       "test: saves a file in on_shutdown after a while, reports it")
LTM_REGISTER_COMPONENT(ltm::tests::Stuck, "test_stuck", "test: blocks in on_shutdown")
LTM_REGISTER_COMPONENT(ltm::tests::BadCloudSource, "test_bad_cloud_source",
                       "test: publishes a float64 PointCloud2")
