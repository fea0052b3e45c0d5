// ltm_eval mesh: accuracy, completeness and Chamfer-L1 of a mesh against the true surface.
#include <iostream>

#include "evaluation/cli/args.hpp"
#include "evaluation/cli/commands.hpp"
#include "evaluation/cli/report.hpp"
#include "evaluation/core/mesh_io.hpp"
#include "evaluation/core/mesh_metric.hpp"

namespace ltm::eval::cli {

const char* const kMeshUsage =
    "usage: ltm_eval mesh --mesh MESH.ply --truth TRUTH.ply [options]\n"
    "  --samples N       samples on each surface (default 200000)\n"
    "  --threshold M     distance for precision / recall / F-score (default 0.1)\n"
    "  --seed N          sampling seed (default 1)\n"
    "  --out DIR         write metrics.txt, metrics.json\n"
    "  A PLY without faces is taken as a point cloud (its points are its samples).\n";

int run_mesh(const std::vector<std::string>& argv) {
    const Args args(argv, {"mesh", "truth", "samples", "threshold", "seed", "out"}, {});
    MeshMetricConfig config;
    const long samples = args.integer("samples", static_cast<long>(config.samples));
    if (samples < 1) throw UsageError("--samples must be positive");
    config.samples = static_cast<std::size_t>(samples);
    config.threshold = args.number("threshold", config.threshold);
    config.seed = static_cast<std::uint64_t>(args.integer("seed", 1));
    const common::PlyMesh mesh = read_mesh_file(args.required("mesh"));
    const common::PlyMesh truth = read_mesh_file(args.required("truth"));

    const MeshMetricResult r = evaluate_mesh(mesh, truth, config);
    Report report("ltm_eval mesh: " + args.get("mesh") + " vs " + args.get("truth"));
    report.section("input");
    report.add_count("mesh_vertices", mesh.vertices.size());
    report.add_count("mesh_triangles", mesh.triangles.size());
    report.add_count("truth_vertices", truth.vertices.size());
    report.add_count("truth_triangles", truth.triangles.size());
    report.add_count("mesh_samples", r.mesh_samples);
    report.add_count("truth_samples", r.truth_samples);
    if (!r.valid) {
        std::cout << report.text();
        throw UsageError("a surface is empty: nothing to compare");
    }
    report.section("mesh");
    report.add("accuracy_mean", r.accuracy_mean, "m");
    report.add("accuracy_p90", r.accuracy_p90, "m");
    report.add("completeness_mean", r.completeness_mean, "m");
    report.add("completeness_p90", r.completeness_p90, "m");
    report.add("chamfer_l1", r.chamfer_l1, "m");
    report.add("threshold", r.threshold, "m");
    report.add("precision", r.precision_pct, "%");
    report.add("recall", r.recall_pct, "%");
    report.add("fscore", r.fscore_pct, "%");
    std::cout << report.text();
    if (args.has("out")) report.write(args.get("out"));
    return 0;
}

}  // namespace ltm::eval::cli
