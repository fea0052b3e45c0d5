#include "bridge/component/scene_topics.hpp"

#include <chrono>

#include "bridge/core/ros2msg_schemas.hpp"
#include "bridge/core/scene_messages.hpp"
#include "common/core/thread_clock.hpp"
#include "runtime/convert/dds_string.hpp"
#include "runtime/convert/geometry.hpp"

namespace ltm::bridge {
namespace {

using runtime::TopicRole;

Stamp stamp_of(const msg::Time& t) { return Stamp{t.sec, t.nanosec}; }

Stamp now_stamp() {
    const auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(
                        std::chrono::system_clock::now().time_since_epoch())
                        .count();
    return Stamp{static_cast<std::int32_t>(ns / 1000000000),
                 static_cast<std::uint32_t>(ns % 1000000000)};
}

Channel ros2_channel(std::uint32_t id, const std::string& topic, const std::string& type) {
    Channel c;
    c.id = id;
    c.topic = topic;
    c.schema_name = type;
    c.schema = ros2msg_schema(type);
    c.schema_encoding = "ros2msg";
    return c;
}

}  // namespace

SceneConfig load_scene_config(runtime::Parameters& p) {
    SceneConfig c;
    c.map = p.get<bool>("map_cloud.enabled", c.map);
    c.rate_hz = p.get<double>("map_cloud.rate_hz", c.rate_hz);
    c.cloud.max_points = static_cast<std::size_t>(
        p.get<int>("map_cloud.max_points", static_cast<int>(c.cloud.max_points)));
    c.cloud.leaf_m = p.get<double>("map_cloud.leaf_m", c.cloud.leaf_m);
    const int kept = p.get<int>("map_cloud.max_kept_points", 0);  // 0: 4 x max_points
    if (kept < 0 || kept > 20000000)
        p.fail("map_cloud.max_kept_points", "must be 0 (4 x max_points) .. 20000000");
    c.cloud.max_kept_points = static_cast<std::size_t>(kept);
    c.mesh = p.get<bool>("mesh_scene", c.mesh);
    if (!(c.rate_hz > 0.0 && c.rate_hz <= 10.0)) p.fail("map_cloud.rate_hz", "must be in (0, 10]");
    if (c.cloud.max_points < 1 || c.cloud.max_points > 2000000)
        p.fail("map_cloud.max_points", "must be 1..2000000");
    if (!(c.cloud.leaf_m > 0.0)) p.fail("map_cloud.leaf_m", "must be > 0");
    return c;
}

SceneTopics::SceneTopics(runtime::ComponentContext& ctx, const SceneConfig& config,
                         std::uint32_t first_channel, Send send)
    : ctx_(ctx), config_(config), send_(std::move(send)), cloud_(config.cloud) {
    std::uint32_t id = first_channel;
    if (config_.map) {
        map_channel_ = id++;
        channels_.push_back(
            ros2_channel(map_channel_, ctx.resolve("map_cloud"), "sensor_msgs/msg/PointCloud2"));
        ctx.subscribe<msg::LocalMap>("local_map", TopicRole::kMap,
                                     [this](const msg::LocalMap& m) { on_local_map(m); });
        ctx.subscribe<msg::PoseGraph>("pose_graph", TopicRole::kMap,
                                      [this](const msg::PoseGraph& g) { on_graph(g); });
        ctx.add_timer(1.0 / config_.rate_hz, [this] { refresh_map(); });
    }
    if (config_.mesh) {
        mesh_channel_ = id++;
        channels_.push_back(ros2_channel(mesh_channel_, ctx.resolve("mesh_scene"),
                                         "foxglove_msgs/msg/SceneUpdate"));
        ctx.subscribe<msg::Mesh>("mesh", TopicRole::kMap,
                                 [this](const msg::Mesh& m) { on_mesh(m); });
    }
}

void SceneTopics::on_local_map(const msg::LocalMap& m) {
    const Eigen::Isometry3f T_anchor_grid = convert::to_isometry(m.grid_in_anchor).cast<float>();
    std::vector<Eigen::Vector3f> points;
    points.reserve(m.voxels._length);
    for (std::uint32_t i = 0; i < m.voxels._length; ++i) {
        const float* c = m.voxels._buffer[i].centre;
        points.push_back(T_anchor_grid * Eigen::Vector3f(c[0], c[1], c[2]));
    }
    const std::string frame = convert::to_string(m.header.frame_id);
    if (!frame.empty()) odom_frame_ = frame;
    cloud_.set_local_map(m.id, convert::to_isometry(m.anchor), std::move(points));
    ctx_.report_memory("map cloud", cloud_.memory_bytes());
}

void SceneTopics::on_graph(const msg::PoseGraph& g) {
    std::map<std::uint64_t, Eigen::Isometry3d> anchors;
    for (std::uint32_t i = 0; i < g.anchors._length; ++i)
        anchors[g.anchors._buffer[i].id] = convert::to_isometry(g.anchors._buffer[i].pose);
    const std::string frame = convert::to_string(g.header.frame_id);
    if (!frame.empty()) map_frame_ = frame;
    cloud_.set_graph(std::move(anchors));
}

void SceneTopics::refresh_map() {
    if (!cloud_.dirty() || map_watchers_.load() == 0) return;
    const auto start = std::chrono::steady_clock::now();
    const double cpu_start = common::thread_cpu_s();
    const MapCloud::Cloud c = cloud_.build();
    auto cdr = std::make_shared<const std::vector<std::uint8_t>>(
        point_cloud2_cdr(c.points, c.in_map_frame ? map_frame_ : odom_frame_, now_stamp()));
    const double cpu_ms = 1000.0 * (common::thread_cpu_s() - cpu_start);
    const double now = std::chrono::duration<double>(start.time_since_epoch()).count();
    if (now - last_report_s_ >= 30.0) {
        last_report_s_ = now;
        const double ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count();
        ctx_.log().info("map cloud: " + std::to_string(c.points.size()) + " points of " +
                        std::to_string(c.input_points) + " (" +
                        std::to_string(cloud_.local_maps()) + " local maps, leaf " +
                        std::to_string(c.leaf_m) + " m), " + std::to_string(cdr->size()) +
                        " B, built in " + std::to_string(cpu_ms) + " ms CPU (" +
                        std::to_string(ms) + " ms wall)");
    }
    send_(map_channel_, std::move(cdr), "");
}

void SceneTopics::on_mesh(const msg::Mesh& m) {
    MeshChunk chunk;
    chunk.id = "mesh/" + std::to_string(m.local_map_id);
    chunk.frame_id = convert::to_string(m.header.frame_id);
    chunk.stamp = stamp_of(m.header.stamp);
    chunk.pose = convert::to_isometry(m.anchor);
    const std::size_t vertices = m.vertices._length / 3;
    bool valid = m.vertices._length % 3 == 0 && m.triangles._length % 3 == 0;
    for (std::uint32_t i = 0; valid && i < m.triangles._length; ++i)
        valid = m.triangles._buffer[i] < vertices;
    if (!valid) {
        if (bad_meshes_++ == 0)
            ctx_.log().warn("mesh chunk " + std::to_string(m.local_map_id) +
                            " not drawn: its vertex or triangle count is not a multiple of 3 or an "
                            "index is out of range (further ones are not logged)");
        return;
    }
    chunk.vertices.assign(m.vertices._buffer, m.vertices._buffer + m.vertices._length);
    chunk.triangles.assign(m.triangles._buffer, m.triangles._buffer + m.triangles._length);
    send_(mesh_channel_, std::make_shared<const std::vector<std::uint8_t>>(scene_update_cdr(chunk)),
          chunk.id);
}

}  // namespace ltm::bridge
