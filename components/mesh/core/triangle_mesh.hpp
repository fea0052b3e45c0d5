#pragma once
// Operations on a triangle mesh (common::PlyMesh: vertices, optional vertex normals, triangles):
// moving it, joining meshes, its area, vertex normals, and a sub-mesh of chosen triangles.
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "common/core/ply_io.hpp"

namespace ltm::mesh {

// Area-weighted face normals summed at each vertex, unit length (zero for a vertex of no face).
std::vector<Eigen::Vector3f> vertex_normals(const common::PlyMesh& mesh);

// The mesh with every vertex (and normal) moved by T.
common::PlyMesh transformed(const common::PlyMesh& mesh, const Eigen::Isometry3d& T);

// Appends `part` moved by T to `into` (normals kept only when both have them, or `into` is empty).
void append(common::PlyMesh& into, const common::PlyMesh& part,
            const Eigen::Isometry3d& T = Eigen::Isometry3d::Identity());

// The triangles t with keep[t] != 0 and the vertices they use (in their order).
common::PlyMesh sub_mesh(const common::PlyMesh& mesh, const std::vector<std::uint8_t>& keep);

// Total area [m^2]; triangles with bad indices count nothing.
double surface_area(const common::PlyMesh& mesh);

// Centroid of triangle t (indices assumed valid).
Eigen::Vector3f centroid(const common::PlyMesh& mesh, std::size_t t);

}  // namespace ltm::mesh
