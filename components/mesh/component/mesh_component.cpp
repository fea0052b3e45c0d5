// The dense mesh as a component: finished local maps in (`local_map`, the odometry's; snapshots of
// maps still being built are skipped) with the optimised anchors (`pose_graph`, the mapping's);
// out `mesh` (ltm_msgs/Mesh), one message per chunk whose owned triangles or pose changed (its
// triangles in its anchor frame, with its current T_map_anchor), and lines on the shared `status`.
// A MeshAtlas (mesh/core) keeps one chunk per local map, placed by the graph.
//
// The global mesh (PLY, map frame) is written at shutdown to `mesh_file` and on request: a
// `map_request` with command WRITE_MESH (`./ltm map mesh`), to the request's global_map_file or
// else `mesh_file`; the answer on `status` has code kMapRequestDone or kMapRequestFailed and the
// request's id (request_id; its message starts "request <id>: "), as the mapping component's.
// Other commands are the mapping component's and are left alone.
//
// Threads: the component's thread takes the inputs; the atlas lives on a worker thread, which
// takes the maps in order, applies the newest graph, updates the ownership, meshes the places a
// chunk owns and has not meshed yet (`threads` chunks at once) and publishes the changed chunks;
// requests go first. At most `max_queue` maps wait for the worker: then the
// oldest is dropped (skip_while_busy, live) or the component's thread waits (offline). At shutdown
// the worker finishes what waits, then the mesh file is written.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <mutex>
#include <optional>

#include "common/core/one_line.hpp"
#include "common/core/ply_io.hpp"
#include "mesh/component/mesh_messages.hpp"
#include "mesh/component/mesh_params.hpp"
#include "mesh/core/mesh_atlas.hpp"
#include "runtime/component.hpp"
#include "runtime/convert/dds_string.hpp"
#include "runtime/convert/geometry.hpp"
#include "runtime/convert/status.hpp"
#include "runtime/worker.hpp"

namespace ltm::mesh {
namespace {

namespace fs = std::filesystem;
using common::StatusCode;
using convert::StatusLevel;
using runtime::TopicRole;
using Clock = std::chrono::steady_clock;
using runtime::StopToken;

double ms_since(Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

struct MapInput {
    common::LocalMapData map;
    msg::Time stamp{};
};

struct GraphInput {
    std::map<std::uint64_t, Eigen::Isometry3d> anchors;
    std::uint32_t revision = 0;
    std::string frame_id;
    msg::Time stamp{};
};

struct Request {
    std::uint32_t id = 0;
    std::string file;  // "": the component's mesh_file
};

using Worker = runtime::Worker<MapInput, GraphInput>;

class MeshComponent : public runtime::Component {
  public:
    explicit MeshComponent(runtime::ComponentContext& ctx)
        : ctx_(ctx),
          config_(load_mesh_params(ctx.params())),
          atlas_(config_.mesh),
          worker_(
              {ctx.name(), "work", std::size_t(config_.max_queue),
               config_.skip_while_busy ? runtime::BusyPolicy::kDropOldest
                                       : runtime::BusyPolicy::kBlock},
              [this](Worker::Step& step, const StopToken& stop) { work(step, stop); },
              [this](const std::string& what) {
                  event(StatusLevel::kError, StatusCode::kMeshFailed, common::one_line(what),
                        stamp_);
              }) {
        frame_id_ = config_.frame_id;
        ctx.subscribe<msg::LocalMap>("local_map", TopicRole::kMap,
                                     [this](const msg::LocalMap& m) { on_local_map(m); });
        ctx.subscribe<msg::PoseGraph>("pose_graph", TopicRole::kMap,
                                      [this](const msg::PoseGraph& m) { on_graph(m); });
        ctx.subscribe<msg::MapRequest>("map_request", TopicRole::kState,
                                       [this](const msg::MapRequest& m) { on_request(m); });
        mesh_out_ = ctx.advertise<msg::Mesh>("mesh", TopicRole::kMap);
        const runtime::QosProfile q = ctx.role_profile("mesh", TopicRole::kMap);
        if (q.transient_local && !q.keep_all) kept_for_late_readers_ = std::size_t(q.depth);
        status_out_ = ctx.advertise<msg::Status>("status", TopicRole::kState);
    }

    ~MeshComponent() override { worker_.stop(); }

    void on_activate() override { worker_.start(); }

    void on_shutdown() override {
        // Finishes the requests, maps and graph that wait, within the stop deadline.
        worker_.stop(ctx_.work_deadline());
        const AtlasTotals t = atlas_.totals();
        char text[300];
        std::snprintf(text, sizeof text,
                      "%zu local maps: %zu taken, %zu snapshots skipped, %zu refused, %zu dropped "
                      "while busy; %zu chunks, %zu triangles owned; %zu meshings: grid %.0f ms, "
                      "marching cubes %.0f ms; updates %.0f ms",
                      maps_, added_, snapshots_, refused_, std::size_t(worker_.skipped()), t.chunks,
                      t.kept_triangles, t.meshings, t.fill_ms, t.mesh_ms, update_ms_);
        ctx_.log().info(text);
        if (!config_.mesh_file.empty()) {
            std::string line;
            const bool ok = write_mesh(config_.mesh_file, nullptr, &line);
            const auto colon = line.find(": ");  // "mesh written to FILE: N vertices, ..."
            ctx_.report_output("mesh", config_.mesh_file, ok,
                               colon == std::string::npos ? line : line.substr(colon + 2));
        }
    }

  private:
    // --- the component's thread: inputs ---

    void on_local_map(const msg::LocalMap& m) {
        ++maps_;
        if (!m.finished) {
            ++snapshots_;
            return;
        }
        MapInput in;
        in.stamp = m.header.stamp;
        try {
            in.map = local_map_from_msg(m);
        } catch (const std::invalid_argument& e) {
            ++refused_;
            event(StatusLevel::kError, StatusCode::kBadLocalMap, common::one_line(e.what()),
                  m.header.stamp);
            return;
        }
        // A newer revision of a map still waiting takes its place.
        worker_.push_merge(std::move(in), [](MapInput& waiting, MapInput& map) {
            if (waiting.map.id != map.map.id) return false;
            if (map.map.revision > waiting.map.revision) waiting = std::move(map);
            return true;
        });
    }

    void on_graph(const msg::PoseGraph& m) {
        GraphInput g;
        try {
            g.anchors = anchors_from_msg(m);
        } catch (const std::invalid_argument& e) {
            event(StatusLevel::kError, StatusCode::kBadPoseGraph, common::one_line(e.what()),
                  m.header.stamp);
            return;
        }
        g.revision = m.revision;
        g.frame_id = convert::to_string(m.header.frame_id);
        g.stamp = m.header.stamp;
        worker_.set_latest(std::move(g));  // only the newest matters
    }

    void on_request(const msg::MapRequest& m) {
        if (m.command != ltm_msgs_msg_MapRequest_Constants_WRITE_MESH) return;  // the mapping's
        // Requests go before the maps that wait.
        worker_.post([this, r = Request{m.id, convert::to_string(m.global_map_file)}](
                         const StopToken&) { answer(r); });
    }

    // --- the worker thread: the atlas ---

    // The next map (if any) and the newest graph (if a new one came). The update runs to its end
    // even when a stop abandons the queue (not the default: it finishes): the global mesh written
    // at shutdown is what the last update left.
    void work(Worker::Step& step, const StopToken&) {
        const bool meshed = step.item && add_map(*step.item);
        const std::optional<GraphInput>& graph = step.latest;
        if (graph) {
            atlas_.set_graph(graph->anchors);
            if (!graph->frame_id.empty()) {
                std::lock_guard<std::mutex> lock(frame_mutex_);
                frame_id_ = graph->frame_id;
            }
            stamp_ = graph->stamp;
        }
        if (meshed || graph) publish_changes();
    }

    // The map's chunk, prepared (voxels, cells); update() meshes the places it owns.
    bool add_map(const MapInput& in) {
        const common::LocalMapData& m = in.map;
        const MeshChunk* have = atlas_.chunk(m.id);
        if (have && have->revision >= m.revision) return false;  // taken already
        try {
            MeshChunk chunk = prepare_chunk(m, config_.mesh);
            ++added_;
            ctx_.log().debug("local map " + std::to_string(m.id) + " revision " +
                             std::to_string(m.revision) + ": " +
                             std::to_string(chunk.voxels.size()) + " surface voxels");
            stamp_ = in.stamp;
            return atlas_.add(std::move(chunk));
        } catch (const std::exception& e) {
            event(StatusLevel::kError, StatusCode::kMeshFailed,
                  "local map " + std::to_string(m.id) + ": " + common::one_line(e.what()),
                  in.stamp);
            return false;
        }
    }

    // Ownership where something changed, the chunks meshed where they own places they have not
    // meshed; one `mesh` message a changed chunk.
    void publish_changes() {
        const AtlasTotals before = atlas_.totals();
        const auto t0 = Clock::now();
        std::vector<std::uint64_t> changed;
        try {
            changed = atlas_.update();
        } catch (const std::exception& e) {
            event(StatusLevel::kError, StatusCode::kMeshFailed, common::one_line(e.what()), stamp_);
            return;
        }
        const double update_ms = ms_since(t0);
        update_ms_ += update_ms;
        for (const std::uint64_t id : changed)
            mesh_out_.publish(*to_msg(placed_chunk(atlas_, id), stamp_, frame_id_));
        const AtlasTotals t = atlas_.totals();
        char text[300];
        std::snprintf(text, sizeof text,
                      "%zu chunks, %zu triangles owned; %zu chunks meshed (grid %.0f ms, marching "
                      "cubes %.0f ms), %zu changed; update %.0f ms",
                      t.chunks, t.kept_triangles, t.meshings - before.meshings,
                      t.fill_ms - before.fill_ms, t.mesh_ms - before.mesh_ms, changed.size(),
                      update_ms);
        event(StatusLevel::kOk, StatusCode::kMeshUpdated, text, stamp_);
        if (kept_for_late_readers_ > 0 && t.chunks > kept_for_late_readers_ && !warned_depth_) {
            warned_depth_ = true;
            event(StatusLevel::kWarn, StatusCode::kMeshDepth,
                  "more chunks than `" + mesh_out_.topic() + "` keeps for late readers (" +
                      std::to_string(kept_for_late_readers_) +
                      " messages): they get the chunks that changed last (qos: map: depth)",
                  stamp_);
        }
    }

    void answer(const Request& r) {
        const std::string file = r.file.empty() ? config_.mesh_file : r.file;
        std::string outcome;
        bool ok = false;
        if (file.empty()) {
            outcome = "nowhere to write: no mesh file in the request or the component's mesh_file";
        } else {
            ok = write_mesh(file, &outcome);
        }
        event(ok ? StatusLevel::kOk : StatusLevel::kError,
              ok ? StatusCode::kMapRequestDone : StatusCode::kMapRequestFailed,
              "request " + std::to_string(r.id) + ": " + outcome, stamp_, r.id);
    }

    // The global mesh as PLY (its folder created); says how it went on `status` (or in
    // `outcome`, for a request's answer).
    bool write_mesh(const std::string& file, std::string* outcome, std::string* text = nullptr) {
        std::string line;
        bool ok = false;
        try {
            const common::PlyMesh mesh = atlas_.global_mesh();
            const fs::path parent = fs::path(file).parent_path();
            if (!parent.empty()) fs::create_directories(parent);
            common::write_ply(file, mesh);
            line = "mesh written to " + file + ": " + std::to_string(mesh.vertices.size()) +
                   " vertices, " + std::to_string(mesh.triangles.size()) + " triangles (" +
                   std::to_string(atlas_.totals().chunks) + " chunks)";
            ok = true;
        } catch (const std::exception& e) {
            line = "mesh not written to " + file + ": " + common::one_line(e.what());
        }
        if (text) *text = line;
        if (outcome) {
            convert::log_status(ctx_.log(), ok ? StatusLevel::kOk : StatusLevel::kError, line);
            *outcome = line;
        } else {
            event(ok ? StatusLevel::kOk : StatusLevel::kError,
                  ok ? StatusCode::kMeshWritten : StatusCode::kMeshNotWritten, line, stamp_);
        }
        return ok;
    }

    // Thread-safe: the publisher and the logger are.
    void event(StatusLevel level, StatusCode code, const std::string& text, const msg::Time& stamp,
               std::uint32_t request_id = 0) {
        convert::log_status(ctx_.log(), level, text);
        status_out_.publish(*convert::to_msg(
            convert::StatusData{stamp, frame_id(), ctx_.name(), level, code, text, 0, request_id}));
    }

    std::string frame_id() {
        std::lock_guard<std::mutex> lock(frame_mutex_);
        return frame_id_;
    }

    runtime::ComponentContext& ctx_;
    const MeshComponentConfig config_;

    // The component's thread.
    std::size_t maps_ = 0, snapshots_ = 0, refused_ = 0;

    // The worker's (read by on_shutdown after the join).
    MeshAtlas atlas_;
    std::mutex frame_mutex_;
    std::string frame_id_;
    msg::Time stamp_{};
    std::size_t added_ = 0;
    double update_ms_ = 0.0;                 // atlas updates: ownership and meshing
    std::size_t kept_for_late_readers_ = 0;  // the mesh topic's history (0: all, or none)
    bool warned_depth_ = false;

    runtime::Publisher<msg::Mesh> mesh_out_;
    runtime::Publisher<msg::Status> status_out_;
    Worker worker_;  // last: stopped before the members it uses go
};

}  // namespace
}  // namespace ltm::mesh

LTM_REGISTER_COMPONENT(
    ltm::mesh::MeshComponent, "mesh",
    "dense mesh: finished local maps and the pose graph in; mesh chunks out, global mesh PLY")
