// ltm_eval mesh: accuracy, completeness and Chamfer-L1 of a mesh against the true surface.
#include <iostream>
#include <memory>

#include "evaluation/cli/commands.hpp"
#include "evaluation/cli/report.hpp"
#include "evaluation/core/mesh_io.hpp"
#include "evaluation/core/mesh_metric.hpp"

namespace ltm::eval::cli {

namespace {

struct MeshOptions {
    std::string mesh, truth, out, crop_to, misses_out;
    MeshMetricConfig config;
};

int run_mesh(const MeshOptions& o) {
    const MeshMetricConfig& config = o.config;
    const common::PlyMesh mesh = read_mesh_file(o.mesh);
    const common::PlyMesh truth = read_mesh_file(o.truth);

    std::vector<Eigen::Vector3d> crop;
    if (!o.crop_to.empty())
        for (const Eigen::Vector3f& p : read_mesh_file(o.crop_to).vertices)
            crop.push_back(p.cast<double>());
    const MeshMetricResult r = evaluate_mesh(mesh, truth, config, crop);
    Report report("ltm_eval mesh: " + o.mesh + " vs " + o.truth);
    report.section("input");
    report.add_count("mesh_vertices", mesh.vertices.size());
    report.add_count("mesh_triangles", mesh.triangles.size());
    report.add_count("truth_vertices", truth.vertices.size());
    report.add_count("truth_triangles", truth.triangles.size());
    report.add_count("mesh_samples", r.mesh_samples);
    report.add_count("truth_samples", r.truth_samples);
    if (!o.crop_to.empty()) report.add_count("truth_samples_cropped", r.truth_cropped);
    if (!r.valid) {
        std::cout << report.text();
        throw UsageError("a surface is empty: nothing to compare");
    }
    report.section("mesh");
    report.add("accuracy_mean", r.accuracy_mean, "m");
    report.add("accuracy_median", r.accuracy_median, "m");
    report.add("accuracy_p90", r.accuracy_p90, "m");
    report.add("completeness_mean", r.completeness_mean, "m");
    report.add("completeness_median", r.completeness_median, "m");
    report.add("completeness_p90", r.completeness_p90, "m");
    report.add("chamfer_l1", r.chamfer_l1, "m");
    report.add("threshold", r.threshold, "m");
    report.add("precision", r.precision_pct, "%");
    report.add("recall", r.recall_pct, "%");
    report.add("fscore", r.fscore_pct, "%");
    if (r.mesh_area > 0.0 && r.truth_area_scored > 0.0) {
        report.add("mesh_area", r.mesh_area, "m^2");
        report.add("truth_area_scored", r.truth_area_scored, "m^2");
        // Near recall / 100 for one surface; a double surface adds its copies' area.
        report.add("area_ratio", r.mesh_area / r.truth_area_scored, "");
    }
    std::cout << report.text();
    if (!o.out.empty()) report.write(o.out);
    if (!o.misses_out.empty()) {
        // Red: true surface the mesh misses; blue: mesh far from the true surface.
        common::PlyCloud c;
        for (const Eigen::Vector3d& p : r.missed) {
            c.points.push_back(p.cast<float>());
            c.intensity.push_back(1.0f);
        }
        for (const Eigen::Vector3d& p : r.wrong) {
            c.points.push_back(p.cast<float>());
            c.intensity.push_back(0.0f);
        }
        common::write_ply(o.misses_out, c);
    }
    return 0;
}

}  // namespace

Run add_mesh(CLI::App& parent) {
    CLI::App* app =
        parent.add_subcommand("mesh", "mesh accuracy, completeness, Chamfer-L1 against the truth");
    app->footer("A PLY without faces is taken as a point cloud (its points are its samples).");
    auto o = std::make_shared<MeshOptions>();
    app->add_option("--mesh", o->mesh, "the mesh to score (.ply)")->required();
    app->add_option("--truth", o->truth, "the true surface (.ply)")->required();
    app->add_option("--samples", o->config.samples, "samples on each surface")
        ->check(common::cli::at_least(1));
    app->add_option("--threshold", o->config.threshold,
                    "distance for precision / recall / F-score [m]");
    app->add_option("--seed", o->config.seed, "sampling seed");
    app->add_option("--crop-to", o->crop_to,
                    "points of what was observed (.ply): truth samples farther than --crop-radius "
                    "from them are not scored");
    app->add_option("--crop-radius", o->config.crop_radius, "[m] for --crop-to")
        ->check(common::cli::at_least(0.001));
    app->add_option("--out", o->out, "write metrics.txt, metrics.json here");
    app->add_option("--misses-out", o->misses_out,
                    "write the samples beyond the threshold as PLY: intensity 1 true surface the "
                    "mesh misses, 0 mesh far from the true surface");
    return [o] { return run_mesh(*o); };
}

}  // namespace ltm::eval::cli
