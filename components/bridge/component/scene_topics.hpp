#pragma once
// What the bridge makes for Foxglove's 3D panel from ltm's own map topics (ltm's types, which
// Foxglove decodes but does not draw): `map_cloud`, the local maps (`local_map`) placed by the
// pose graph (`pose_graph`) and decimated to at most `max_points` (sensor_msgs/msg/PointCloud2),
// refreshed at most `rate_hz` and only while a client watches; `mesh_scene`, each mesh chunk
// (`mesh`) as a foxglove_msgs/msg/SceneUpdate triangle list. Both keep their last message(s) for
// a client that subscribes later.
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "bridge/core/foxglove_protocol.hpp"
#include "bridge/core/map_cloud.hpp"
#include "runtime/component_context.hpp"

namespace ltm::bridge {

struct SceneConfig {
    bool map = true;       // the map cloud
    bool mesh = true;      // the mesh chunks
    double rate_hz = 1.0;  // the map cloud's refresh, at most [Hz]
    MapCloudConfig cloud;  // max_points, leaf_m
};

// Reads `map_cloud.*` and `mesh_scene` parameters (names the key of a bad value).
SceneConfig load_scene_config(runtime::Parameters& p);

class SceneTopics {
  public:
    // A message for a channel; `key` names what it replaces for a late subscriber ("" for the
    // whole channel, the entity id for a mesh chunk).
    using Send = std::function<void(std::uint32_t channel,
                                    std::shared_ptr<const std::vector<std::uint8_t>> cdr,
                                    const std::string& key)>;

    // Channel ids from `first_channel` on. Subscribes on `ctx`'s thread; `send` is called there.
    SceneTopics(runtime::ComponentContext& ctx, const SceneConfig& config,
                std::uint32_t first_channel, Send send);

    const std::vector<Channel>& channels() const { return channels_; }
    std::uint32_t map_channel() const { return map_channel_; }
    // Clients subscribed to the map cloud (set by the bridge's io thread): no work while none.
    std::atomic<int>& map_watchers() { return map_watchers_; }

  private:
    void on_local_map(const msg::LocalMap& m);
    void on_graph(const msg::PoseGraph& g);
    void on_mesh(const msg::Mesh& m);
    void refresh_map();

    runtime::ComponentContext& ctx_;
    SceneConfig config_;
    Send send_;
    std::vector<Channel> channels_;
    std::uint32_t map_channel_ = 0, mesh_channel_ = 0;
    MapCloud cloud_;
    std::string odom_frame_ = "odom", map_frame_ = "map";
    std::atomic<int> map_watchers_{0};
    std::uint64_t bad_meshes_ = 0;
    double last_report_s_ = -1e9;  // the map cloud's size and build time, in the log every 30 s
};

}  // namespace ltm::bridge
