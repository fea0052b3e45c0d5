#pragma once
// Surface reconstruction quality of a mesh against the true surface, both sampled uniformly by
// area (a fixed seed):
//   accuracy     distances from samples of the mesh to the true surface (mean, 90th percentile)
//   completeness distances from samples of the true surface to the mesh (mean, 90th percentile)
//   Chamfer-L1   (accuracy mean + completeness mean) / 2
//   precision / recall / F-score: the share of mesh (truth) samples within `threshold` of the
//   truth (mesh), and their harmonic mean.
// Distances are exact point-to-triangle distances. A "mesh" with no triangles is taken as a
// point cloud: its samples are its points and distances go to its nearest point.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "common/core/ply_io.hpp"

namespace ltm::eval {

struct MeshMetricConfig {
    std::size_t samples =
        200000;              // samples drawn on each surface (clouds: at most this many points)
    double threshold = 0.1;  // [m] for precision / recall / F-score
    std::uint64_t seed = 1;  // sampling seed
    // With crop points: truth samples farther than this from every crop point are left out (the
    // true surface no scan saw: roofs, the far side of objects, places the route never reached).
    double crop_radius = 0.3;  // [m]
};

struct MeshMetricResult {
    double accuracy_mean = 0.0, accuracy_median = 0.0, accuracy_p90 = 0.0;  // mesh -> truth [m]
    double completeness_mean = 0.0, completeness_median = 0.0,
           completeness_p90 = 0.0;  // truth -> mesh [m]
    double chamfer_l1 = 0.0;        // [m]
    double precision_pct = 0.0, recall_pct = 0.0, fscore_pct = 0.0;
    double threshold = 0.0;  // [m]
    std::size_t mesh_samples = 0, truth_samples = 0;
    std::size_t truth_cropped = 0;  // truth samples left out by the crop
    // Areas [m^2]: the mesh's, and the truth's that is scored (all of it without a crop). A mesh
    // with a double surface (two copies of a wall slightly apart) has about twice the area of
    // the truth it covers.
    double mesh_area = 0.0, truth_area_scored = 0.0;
    // Samples farther than the threshold from the other surface: where the mesh is incomplete
    // (truth samples) and where it is wrong (mesh samples).
    std::vector<Eigen::Vector3d> missed, wrong;
    bool valid = false;  // false when either surface is empty
};

// Area-weighted uniform samples of a mesh's triangles (its points when it has none; a random
// subset of them when there are more than `count`). Triangles with bad indices are skipped.
std::vector<Eigen::Vector3d> sample_surface(const common::PlyMesh& mesh, std::size_t count,
                                            std::uint64_t seed);

// Total area of the valid triangles [m^2].
double mesh_area(const common::PlyMesh& mesh);

// `crop_to` (may be empty): points of what was observed; truth samples farther than
// config.crop_radius from all of them are not scored.
MeshMetricResult evaluate_mesh(const common::PlyMesh& mesh, const common::PlyMesh& truth,
                               const MeshMetricConfig& config = {},
                               const std::vector<Eigen::Vector3d>& crop_to = {});

}  // namespace ltm::eval
