#pragma once
// Reading PLY meshes (and PLY point clouds, which read as meshes without triangles) and coloured
// PLY point clouds with PCL.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "common/core/ply_io.hpp"

namespace ltm::eval {

// Vertices and triangles of a PLY file (ASCII or binary); polygons with more than three vertices
// are split into fans. Throws common::IoError with a one-line reason on failure.
common::PlyMesh read_mesh_file(const std::string& path);

// The vertices of a PLY file and their red/green/blue when it has them (else `colours` empty).
struct ColouredCloud {
    std::vector<Eigen::Vector3f> points;
    std::vector<std::array<std::uint8_t, 3>> colours;
};
ColouredCloud read_coloured_cloud(const std::string& path);

}  // namespace ltm::eval
