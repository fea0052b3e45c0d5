// A one-shot client of the mapping component: once a mapping component listens on `map_request`,
// asks it to save the map and/or write the global map (command `mesh`: asks the mesh component to
// write the global mesh, to `mesh_file`), waits for its answer on `status` and finishes (the host
// then exits 0). The request goes out once the readers on `map_request` stopped growing for a tick
// (the mapping and the mesh component of one host are found together). No answer within
// `timeout_s`, or a refused request, fails the component (the host exits 1) with one line saying
// why. `./ltm map` runs it.
#include <unistd.h>

#include <chrono>
#include <stdexcept>

#include "runtime/component.hpp"
#include "runtime/convert/dds_string.hpp"
#include "runtime/convert/owned_message.hpp"
#include "runtime/convert/status.hpp"

namespace ltm::mapping {
namespace {

using runtime::PathCheck;
using runtime::TopicRole;

class MapRequestComponent : public runtime::Component {
  public:
    explicit MapRequestComponent(runtime::ComponentContext& ctx) : ctx_(ctx) {
        auto& p = ctx.params();
        const std::string what = p.get<std::string>("command", "all");
        if (what == "save") {
            command_ = ltm_msgs_msg_MapRequest_Constants_SAVE_MAP;
        } else if (what == "global_map") {
            command_ = ltm_msgs_msg_MapRequest_Constants_WRITE_GLOBAL_MAP;
        } else if (what == "all") {
            command_ = ltm_msgs_msg_MapRequest_Constants_SAVE_ALL;
        } else if (what == "mesh") {
            command_ = ltm_msgs_msg_MapRequest_Constants_WRITE_MESH;
            answerer_ = "mesh";
        } else if (what == "commit") {
            command_ = ltm_msgs_msg_MapRequest_Constants_COMMIT_VERSION;
            answerer_ = "site";
        } else {
            p.fail("command", "expected save, global_map, all, mesh or commit, got '" + what + "'");
        }
        map_dir_ = p.path("map_dir", "", PathCheck::kParentExists);
        global_map_file_ = p.path("global_map_file", "", PathCheck::kParentExists);
        const std::string mesh_file = p.path("mesh_file", "", PathCheck::kParentExists);
        const bool mesh = command_ == ltm_msgs_msg_MapRequest_Constants_WRITE_MESH;
        const bool commit = command_ == ltm_msgs_msg_MapRequest_Constants_COMMIT_VERSION;
        if (commit && (!map_dir_.empty() || !global_map_file_.empty() || !mesh_file.empty()))
            p.fail("command", "commit takes no file: the site commits its own staging");
        if (!mesh && !mesh_file.empty()) p.fail("mesh_file", "only with command mesh");
        if (mesh && !map_dir_.empty()) p.fail("map_dir", "not with command mesh");
        if (mesh && !global_map_file_.empty())
            p.fail("global_map_file", "not with command mesh (its file: mesh_file)");
        if (mesh) global_map_file_ = mesh_file;  // the request's field names the mesh PLY
        timeout_s_ = p.get<double>("timeout_s", 30.0);
        if (!(timeout_s_ > 0)) p.fail("timeout_s", "must be > 0");
        // Unique enough among requesters of one robot: the process id and the clock.
        id_ =
            static_cast<std::uint32_t>(::getpid()) * 7919u +
            static_cast<std::uint32_t>(std::chrono::steady_clock::now().time_since_epoch().count());
        ctx.declare_source();
        request_out_ = ctx.advertise<msg::MapRequest>("map_request", TopicRole::kState);
        ctx.subscribe<msg::Status>("status", TopicRole::kState,
                                   [this](const msg::Status& s) { on_status(s); });
        ctx.add_timer(0.1, [this] { tick(); });
    }

  private:
    void tick() {
        if (done_) return;
        const auto now = std::chrono::steady_clock::now();
        if (!started_) {
            started_ = true;
            start_ = now;
        }
        const std::uint32_t readers = request_out_.matched();
        const bool settled = readers > 0 && readers == last_readers_;
        last_readers_ = readers;
        if (!sent_ && settled) {
            convert::Owned<msg::MapRequest> r;
            r->id = id_;
            r->command = command_;
            convert::set_string(r->map_dir, map_dir_);
            convert::set_string(r->global_map_file, global_map_file_);
            request_out_.publish(*r);
            sent_ = true;
            ctx_.log().info("request " + std::to_string(id_) + " sent");
        }
        if (std::chrono::duration<double>(now - start_).count() > timeout_s_) {
            done_ = true;
            throw std::runtime_error(
                sent_ ? "no answer from the " + answerer_ + " component within " + fmt(timeout_s_) +
                            " s"
                      : "no " + answerer_ + " component listens on '" + request_out_.topic() +
                            "' (is it running, on the same domain and namespace?)");
        }
    }

    void on_status(const msg::Status& m) {
        const convert::StatusData s = convert::from_msg(m);
        if (done_ || s.request_id != id_) return;
        const bool failed = s.code == common::StatusCode::kMapRequestFailed;
        if (!failed && s.code != common::StatusCode::kMapRequestDone) return;  // not an answer
        done_ = true;
        // The answer's text without its "request <id>: " (said in our own log line).
        const std::string prefix = "request " + std::to_string(id_) + ": ";
        const std::string text =
            s.message.rfind(prefix, 0) == 0 ? s.message.substr(prefix.size()) : s.message;
        if (failed) throw std::runtime_error(text);
        ctx_.log().info(text);
        ctx_.finished();
    }

    static std::string fmt(double v) {
        std::string s = std::to_string(v);
        s.erase(s.find_last_not_of('0') + 1);
        if (!s.empty() && s.back() == '.') s.pop_back();
        return s;
    }

    runtime::ComponentContext& ctx_;
    std::uint8_t command_ = ltm_msgs_msg_MapRequest_Constants_SAVE_ALL;
    std::string map_dir_, global_map_file_;
    std::string answerer_ = "mapping";  // the component the command is for
    std::uint32_t last_readers_ = 0;
    double timeout_s_ = 30.0;
    std::uint32_t id_ = 0;
    bool started_ = false, sent_ = false, done_ = false;
    std::chrono::steady_clock::time_point start_;
    runtime::Publisher<msg::MapRequest> request_out_;
};

}  // namespace
}  // namespace ltm::mapping

LTM_REGISTER_COMPONENT(
    ltm::mapping::MapRequestComponent, "map_request",
    "asks a running mapping component to save its map / global map (or the mesh component to "
    "write its mesh), waits for the answer")
