// The budget benchmark's probe (`./ltm bench budget`): for every sample of its inputs the header
// stamp, the writer's source timestamp (wall clock, DDS sets it at the write) and the time it
// arrived, written as CSV at shutdown. Samples are taken as raw CDR: a scan is not decoded.
//   inputs: [points, odometry, pose, map_changes]   (any subset; remap them as usual)
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "bench/budget/cdr_stamp.hpp"
#include "bench/budget/proc_stat.hpp"
#include "runtime/component.hpp"

namespace ltm::bench {
namespace {

using runtime::TopicRole;

struct Input {
    const char* topic;
    TopicRole role;
    const dds_topic_descriptor_t* desc;
};

class BudgetProbe : public runtime::Component {
  public:
    explicit BudgetProbe(runtime::ComponentContext& ctx) : ctx_(ctx) {
        auto& p = ctx.params();
        file_ = p.get<std::string>("file", "");
        if (file_.empty()) p.fail("file", "required parameter is missing (the CSV to write)");
        const auto inputs = p.get<std::vector<std::string>>(
            "inputs", {"points", "odometry", "pose", "map_changes"});
        const Input known[] = {
            {"points", TopicRole::kSensor, runtime::MessageTraits<msg::PointCloud2>::descriptor()},
            {"odometry", TopicRole::kState, runtime::MessageTraits<msg::Odometry>::descriptor()},
            {"pose", TopicRole::kState,
             runtime::MessageTraits<msg::PoseWithCovarianceStamped>::descriptor()},
            {"map_changes", TopicRole::kMap,
             runtime::MessageTraits<msg::MapChangeSet>::descriptor()},
        };
        for (const auto& name : inputs) {
            const Input* in = nullptr;
            for (const auto& k : known)
                if (name == k.topic) in = &k;
            if (!in)
                p.fail("inputs",
                       "unknown input '" + name + "' (points, odometry, pose, map_changes)");
            auto qos = ctx.role_profile(in->topic, in->role);
            if (!qos.keep_all) qos.depth = std::max(qos.depth, 1000);  // the probe never drops
            const std::string topic = in->topic;
            ctx.subscribe_raw(
                topic, in->desc, qos,
                [this, topic](const std::vector<std::uint8_t>& cdr, const dds_sample_info_t& info) {
                    const auto stamp = cdr_header_stamp(cdr.data(), cdr.size());
                    if (!stamp) return;
                    rows_.push_back(
                        {topic, *stamp, 1e-9 * double(info.source_timestamp), realtime_now_s()});
                });
        }
    }

    void on_shutdown() override {
        std::FILE* f = std::fopen(file_.c_str(), "w");
        if (!f) {
            ctx_.report_output("budget probe", file_, false, "cannot write");
            return;
        }
        std::fprintf(f, "topic,stamp,sent,received\n");
        for (const auto& r : rows_)
            std::fprintf(f, "%s,%.6f,%.6f,%.6f\n", r.topic.c_str(), r.stamp, r.sent, r.received);
        const bool ok = std::fclose(f) == 0;
        ctx_.report_output("budget probe", file_, ok, std::to_string(rows_.size()) + " samples");
    }

  private:
    struct Row {
        std::string topic;
        double stamp, sent, received;
    };
    runtime::ComponentContext& ctx_;
    std::string file_;
    std::vector<Row> rows_;
};

}  // namespace
}  // namespace ltm::bench

LTM_REGISTER_COMPONENT(
    ltm::bench::BudgetProbe, "budget_probe",
    "records the stamp and source time of every sample of its inputs (bench budget)")
