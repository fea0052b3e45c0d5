#pragma once
// Configuration of the dense mesh (METHOD.md section 4, Eq. 11): the signed-distance grid filled
// from a local map's voxels (centre c, unit normal n: sdf(q) = n . (q - c)), its truncation and
// weights, the marching-cubes surface, and how overlapping local maps share space.
#include <optional>
#include <string>

#include "common/core/config_check.hpp"

namespace ltm::mesh {

struct MeshConfig {
    // [m] edge of the signed-distance grid's cells; 0: a third of the local map's voxel size.
    double grid_size = 0.0;
    // [m] |n . (q - c)| beyond this is not written (the narrow band); 0: 2 grid cells.
    double truncation = 0.0;
    // A voxel writes the grid points within this many of its voxel sizes of its centre, measured
    // in its plane (a plane patch a little larger than the voxel, so neighbours overlap and blend).
    double support = 1.0;
    // Weight of a voxel at grid point q: base * exp(-|q - c|^2 / (kernel * voxel_size)^2), the
    // implicit moving least squares weight the odometry's surface uses (Eq. 4); base is
    // planarity_floor + planarity, times the voxel's health when use_health.
    double kernel = 0.6;
    double planarity_floor = 0.1;
    bool use_health = true;
    // Voxels with fewer points are left out.
    int min_points = 3;
    // A grid point needs this much summed weight to count (a surface ends where its support ends).
    double min_weight = 0.05;
    // Overlapping local maps: a place belongs to the local map with the nearest anchor among
    // those that have a voxel in its ownership cell (this many voxel sizes on a side, in that
    // map's lattice); each map keeps only the triangles of the places it owns.
    double ownership_cell = 2.0;
    // A chunk meshes the places it owns and this many ownership cells around them (so that its
    // surface reaches across the seam, and anchors may move a little before it must mesh more).
    int ownership_margin = 1;
    // A chunk is meshed again when more than this share of the cells it owns is not meshed (after
    // anchors moved); until then the chunks that meshed those places keep their surface there.
    double remesh_fraction = 0.05;
    // [m] After an optimisation, ownership is worked out again for the chunks whose neighbours
    // moved relative to them by more than this (at the chunk's edge); below it the seams stay
    // where they were (an overlap or gap of at most this much).
    double ownership_tolerance = 0.1;
    // Vertex normals (area-weighted face normals), for shading in viewers.
    bool vertex_normals = true;
    // Local maps a MeshAtlas meshes at once (0: one a core). One keeps a core free for the
    // odometry on the robot; the base station or an offline run may use more.
    int threads = 1;
};

template <class Visitor>
void visit_fields(MeshConfig& c, const std::string& prefix, Visitor&& v) {
    using namespace common::rules;
    v(prefix + "grid_size", c.grid_size, zero_or_in(0.005, 5.0));
    v(prefix + "truncation", c.truncation, non_negative);
    v(prefix + "support", c.support, in_range(0.25, 5.0));
    v(prefix + "kernel", c.kernel, in_range(0.05, 5.0));
    v(prefix + "planarity_floor", c.planarity_floor, in_range(0.0, 10.0));
    v(prefix + "use_health", c.use_health, unchecked);
    v(prefix + "min_points", c.min_points, at_least(1));
    v(prefix + "min_weight", c.min_weight, non_negative);
    v(prefix + "ownership_cell", c.ownership_cell, in_range(0.5, 50.0));
    v(prefix + "ownership_margin", c.ownership_margin, in_range(0, 10));
    v(prefix + "remesh_fraction", c.remesh_fraction, unit);
    v(prefix + "ownership_tolerance", c.ownership_tolerance, non_negative);
    v(prefix + "vertex_normals", c.vertex_normals, unchecked);
    v(prefix + "threads", c.threads, in_range(0, 256));
}

// The first problem of a configuration (key relative to it), rules across fields included.
std::optional<common::ConfigProblem> validate(const MeshConfig& config);

// The grid cell and truncation actually used for a local map of `voxel_size`.
double effective_grid_size(const MeshConfig& config, double voxel_size);
double effective_truncation(const MeshConfig& config, double voxel_size);

}  // namespace ltm::mesh
