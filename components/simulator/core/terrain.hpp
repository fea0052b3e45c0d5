#pragma once
// Ground surface: a height field on a regular grid (gentle procedural slopes, optionally pulled
// through the ground points under a recorded path), triangulated exactly as height() reads it.
#include <Eigen/Geometry>
#include <cstdint>
#include <functional>
#include <vector>

#include "simulator/core/geometry2d.hpp"
#include "simulator/core/mesh.hpp"

namespace ltm::sim {

struct TerrainConfig {
    double amplitude = 1.0;     // [m] peak height of the procedural undulation
    double wavelength = 150.0;  // [m] of the longest undulation (the others are shorter)
    double cell = 2.0;          // [m] grid spacing of the mesh
};

class Terrain {
  public:
    Terrain() = default;
    // Procedural slopes over `region` (x, y); deterministic by seed.
    Terrain(const TerrainConfig& config, const Eigen::AlignedBox2d& region, std::uint64_t seed);

    // Pulls the surface through ground points (x, y, z) (e.g. under a recorded vehicle path):
    // near them the height is their inverse-distance mean, farther away the procedural
    // undulation fades in on top of it.
    void anchor(const std::vector<Eigen::Vector3d>& ground, double radius = 40.0);
    // Keeps only cells within `radius` of the samples in the mesh (the rest is never in range).
    void restrict_to(const Points2& samples, double radius);

    // True when (x, y) lies on a cell kept in the mesh.
    bool covered(double x, double y) const;
    // Height of the triangulated surface [m] (clamped at the region border).
    double height(double x, double y) const;
    // Smoothed unit normal (central differences over about a cell).
    Eigen::Vector3d normal(double x, double y) const;
    // Lowest and highest surface height over a footprint.
    Eigen::Vector2d height_range(const OrientedRect& r) const;

    // Appends the kept cells (object id 0); the material is chosen per triangle centre.
    void append_mesh(Mesh& mesh,
                     const std::function<Material(const Eigen::Vector2d&)>& material) const;

    const Eigen::AlignedBox2d& region() const { return region_; }

  private:
    double at(int i, int j) const { return heights_[static_cast<std::size_t>(j) * nx_ + i]; }
    Eigen::Vector2d vertex_xy(int i, int j) const;

    TerrainConfig config_;
    Eigen::AlignedBox2d region_;
    int nx_ = 0, ny_ = 0;  // vertices
    std::vector<float> heights_;
    std::vector<std::uint8_t> keep_;  // per cell
};

}  // namespace ltm::sim
