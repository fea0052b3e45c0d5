#pragma once
// Reading PLY meshes (and PLY point clouds, which read as meshes without triangles) with PCL.
#include <string>

#include "common/core/ply_io.hpp"

namespace ltm::eval {

// Vertices and triangles of a PLY file (ASCII or binary); polygons with more than three vertices
// are split into fans. Throws common::IoError with a one-line reason on failure.
common::PlyMesh read_mesh_file(const std::string& path);

}  // namespace ltm::eval
