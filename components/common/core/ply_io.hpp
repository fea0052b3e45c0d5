#pragma once
// PLY output that every viewer opens (binary little-endian): point clouds and triangle meshes.
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

namespace ltm::common {

struct PlyCloud {
    std::vector<Eigen::Vector3f> points;
    std::vector<Eigen::Vector3f> normals;  // empty, or one per point
    std::vector<float> intensity;          // empty, or one per point
};

struct PlyMesh {
    std::vector<Eigen::Vector3f> vertices;
    std::vector<Eigen::Vector3f> normals;    // empty, or one per vertex
    std::vector<Eigen::Vector3i> triangles;  // vertex indices
};

// Written to a temporary file and renamed, so a reader never sees half a file.
// Throws IoError on failure or on channels whose sizes do not match.
void write_ply(const std::string& path, const PlyCloud& cloud);
void write_ply(const std::string& path, const PlyMesh& mesh);

}  // namespace ltm::common
