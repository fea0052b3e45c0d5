#pragma once
// A triangle soup with a material and an object id per triangle, and a builder of the simple
// solids every scene object is made of (boxes, cylinders, frusta, ellipsoids, roofs).
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "simulator/core/materials.hpp"

namespace ltm::sim {

struct Mesh {
    std::vector<Eigen::Vector3f> vertices;
    std::vector<Eigen::Vector3i> triangles;
    std::vector<Material> material;     // one per triangle
    std::vector<std::uint32_t> object;  // one per triangle: object id (0 = terrain)

    std::size_t num_triangles() const { return triangles.size(); }
    void append(const Mesh& other);
    // Bounds of the vertices (empty box for an empty mesh).
    Eigen::AlignedBox3f bounds() const;
};

// Appends shapes, given in a local frame, to a mesh. Not copyable state beyond the target.
class MeshBuilder {
  public:
    explicit MeshBuilder(Mesh& mesh) : mesh_(mesh) {}

    void set_transform(const Eigen::Isometry3d& T_world_local) { T_ = T_world_local; }
    void set_material(Material m) { material_ = m; }
    void set_object(std::uint32_t id) { object_ = id; }

    void triangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c);
    void quad(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
              const Eigen::Vector3d& d);
    // Axis-aligned in the local frame.
    void box(const Eigen::Vector3d& min, const Eigen::Vector3d& max);
    // Round solids from a to b: radius r0 at a, r1 at b, `segments` facets, closed by caps.
    void frustum(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double r0, double r1,
                 int segments, bool caps = true);
    void cylinder(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double r, int segments,
                  bool caps = true) {
        frustum(a, b, r, r, segments, caps);
    }
    // Icosphere (80 faces) scaled to the radii.
    void ellipsoid(const Eigen::Vector3d& center, const Eigen::Vector3d& radii);
    // Gable roof over [min.x, max.x] x [min.y, max.y] at height min.z, ridge along x at max.z.
    void gable_roof(const Eigen::Vector3d& min, const Eigen::Vector3d& max);

  private:
    int vertex(const Eigen::Vector3d& p_local);
    void face(int a, int b, int c);

    Mesh& mesh_;
    Eigen::Isometry3d T_ = Eigen::Isometry3d::Identity();
    Material material_ = Material::kConcrete;
    std::uint32_t object_ = 0;
};

// Pose of an object standing at (x, y, z) turned by yaw [rad] about the vertical.
Eigen::Isometry3d ground_pose(double x, double y, double z, double yaw);

}  // namespace ltm::sim
