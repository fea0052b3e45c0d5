#include "bridge/core/scene_messages.hpp"

#include "bridge/core/cdr_writer.hpp"

namespace ltm::bridge {
namespace {

constexpr std::uint8_t kFloat32 = 7;  // sensor_msgs/PointField FLOAT32

void pose(CdrWriter& w, const Eigen::Isometry3d& T) {
    const Eigen::Quaterniond q(T.rotation());
    for (int i = 0; i < 3; ++i) w.f64(T.translation()[i]);
    w.f64(q.x());
    w.f64(q.y());
    w.f64(q.z());
    w.f64(q.w());
}

void time(CdrWriter& w, Stamp s) {
    w.i32(s.sec);
    w.u32(s.nanosec);
}

}  // namespace

std::vector<std::uint8_t> point_cloud2_cdr(const std::vector<Eigen::Vector3f>& points,
                                           const std::string& frame_id, Stamp stamp) {
    CdrWriter w;
    w.reserve(128 + frame_id.size() + 12 * points.size());
    time(w, stamp);
    w.string(frame_id);
    w.u32(1);                                          // height
    w.u32(static_cast<std::uint32_t>(points.size()));  // width
    w.length(3);
    const char* names[] = {"x", "y", "z"};
    for (std::uint32_t i = 0; i < 3; ++i) {
        w.string(names[i]);
        w.u32(4 * i);  // offset
        w.u8(kFloat32);
        w.u32(1);  // count
    }
    w.boolean(false);                                       // is_bigendian
    w.u32(12);                                              // point_step
    w.u32(static_cast<std::uint32_t>(12 * points.size()));  // row_step
    w.length(12 * points.size());
    for (const Eigen::Vector3f& p : points) w.bytes(p.data(), 12);  // Eigen: x y z contiguous
    w.boolean(true);                                                // is_dense
    return w.take();
}

std::vector<std::uint8_t> scene_update_cdr(const MeshChunk& chunk) {
    CdrWriter w;
    const bool remove = chunk.triangles.empty();
    w.reserve(256 + 24 * (chunk.vertices.size() / 3) + 4 * chunk.triangles.size());
    // deletions
    w.length(remove ? 1 : 0);
    if (remove) {
        time(w, chunk.stamp);
        w.u8(0);  // MATCHING_ID
        w.string(chunk.id);
    }
    // entities
    w.length(remove ? 0 : 1);
    if (!remove) {
        time(w, chunk.stamp);
        w.string(chunk.frame_id);
        w.string(chunk.id);
        time(w, Stamp{});                         // lifetime 0: until replaced or deleted
        w.boolean(true);                          // frame_locked: moves with its frame
        w.length(0);                              // metadata
        for (int i = 0; i < 5; ++i) w.length(0);  // arrows cubes spheres cylinders lines
        w.length(1);                              // triangles
        pose(w, chunk.pose);
        const std::size_t n = chunk.vertices.size() / 3;
        w.length(n);
        for (std::size_t v = 0; v < n; ++v) {
            for (int i = 0; i < 3; ++i) w.f64(chunk.vertices[3 * v + i]);
        }
        for (const float c : {chunk.r, chunk.g, chunk.b, chunk.a}) w.f64(c);
        w.length(0);  // colors
        w.length(chunk.triangles.size());
        for (const std::uint32_t i : chunk.triangles) w.u32(i);
        w.length(0);  // texts
        w.length(0);  // models
    }
    return w.take();
}

}  // namespace ltm::bridge
