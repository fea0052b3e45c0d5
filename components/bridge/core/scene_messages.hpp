#pragma once
// The messages the bridge makes for Foxglove's 3D panel, as CDR (their ros2msg schemas are in
// ros2msg_schemas): the map cloud as sensor_msgs/msg/PointCloud2 (x y z float32) and a mesh chunk
// as foxglove_msgs/msg/SceneUpdate (foxglove.SceneUpdate: one entity, one triangle list).
#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <vector>

namespace ltm::bridge {

struct Stamp {
    std::int32_t sec = 0;
    std::uint32_t nanosec = 0;
};

std::vector<std::uint8_t> point_cloud2_cdr(const std::vector<Eigen::Vector3f>& points,
                                           const std::string& frame_id, Stamp stamp);

struct MeshChunk {
    std::string id;        // the scene entity's id ("mesh/12": one a local map)
    std::string frame_id;  // the frame `pose` is in ("map")
    Stamp stamp;
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  // T_frame_anchor
    std::vector<float> vertices;                             // x y z a vertex, anchor frame
    std::vector<std::uint32_t> triangles;                    // three vertex indices a triangle
    float r = 0.55f, g = 0.62f, b = 0.70f, a = 1.0f;         // one colour for the chunk
};

// The chunk as an entity that replaces the earlier one of its id; an empty chunk (no triangle)
// deletes it instead.
std::vector<std::uint8_t> scene_update_cdr(const MeshChunk& chunk);

}  // namespace ltm::bridge
