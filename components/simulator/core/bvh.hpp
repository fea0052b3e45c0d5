#pragma once
// Bounding-volume hierarchy over the triangles of a Mesh (binned surface-area heuristic,
// 32-byte nodes, ordered stack traversal): closest-hit ray casting for the LiDAR simulator.
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "simulator/core/mesh.hpp"

namespace ltm::sim {

struct RayHit {
    float t = 0.0f;              // distance along the (unit) direction [m]
    std::uint32_t triangle = 0;  // index of the triangle in the mesh the BVH was built from
};

class Bvh {
  public:
    Bvh() = default;
    explicit Bvh(const Mesh& mesh);

    // Closest hit with tmin < t < tmax. `dir` need not be unit; t is in units of |dir|.
    bool intersect(const Eigen::Vector3f& origin, const Eigen::Vector3f& dir, float tmin,
                   float tmax, RayHit& hit) const;
    // Unit geometric normal of mesh triangle `triangle` (orientation arbitrary).
    const Eigen::Vector3f& normal(std::uint32_t triangle) const { return normals_[triangle]; }

    bool empty() const { return nodes_.empty(); }
    std::size_t num_nodes() const { return nodes_.size(); }
    std::size_t num_triangles() const { return tris_.size(); }
    Eigen::AlignedBox3f bounds() const;

  private:
    struct Node {
        float lo[3];
        std::uint32_t first;  // leaf: first triangle slot; inner: left child (right = first + 1)
        float hi[3];
        std::uint32_t count;  // leaf: number of triangles; inner: 0
    };
    struct Tri {
        Eigen::Vector3f v0, e1, e2;
    };

    void build(const Mesh& mesh);
    void subdivide(std::uint32_t node_index, int depth, std::vector<Eigen::AlignedBox3f>& boxes,
                   std::vector<Eigen::Vector3f>& centroids, std::vector<std::uint32_t>& order);

    std::vector<Node> nodes_;
    std::vector<Tri> tris_;                 // in BVH slot order
    std::vector<std::uint32_t> ids_;        // slot -> mesh triangle
    std::vector<Eigen::Vector3f> normals_;  // per mesh triangle
};

}  // namespace ltm::sim
