#include "maintenance/component/maintenance_params.hpp"

#include <gtest/gtest.h>

namespace ltm::maintenance {
namespace {

runtime::Parameters params_of(const std::string& yaml) {
    return runtime::Parameters(YAML::Load(yaml), "test.yaml", "maintenance");
}

std::string error_of(const std::string& yaml) {
    try {
        runtime::Parameters p = params_of(yaml);
        load_maintenance_params(p);
        p.check_all_used();
    } catch (const runtime::ConfigError& e) {
        return e.what();
    }
    return "";
}

TEST(MaintenanceParams, DefaultsThenOverrides) {
    runtime::Parameters p = params_of(
        "input: pose\noutput_dir: /tmp/x\nmap_file: /tmp/m.bin\nmaintain_every_s: 5\nsession: "
        "2\nmax_queue: 9\npack_after: 0\n"
        "skip_while_busy: true\ncpu_share: 0.4\ncpu_budget: background\nmax_queue_mb: "
        "64\nvoxel_size: 0.3\nchange: {sigma: 2.5, voxel_level: "
        "true}\n"
        "ground: {height: 0.4}\n");
    const MaintenanceComponentConfig c = load_maintenance_params(p);
    EXPECT_NO_THROW(p.check_all_used());
    EXPECT_EQ(c.input, PoseInput::kPose);
    EXPECT_EQ(c.output_dir, "/tmp/x");
    EXPECT_EQ(c.map_file, "/tmp/m.bin");
    EXPECT_DOUBLE_EQ(c.maintain_every_s, 5.0);
    EXPECT_EQ(c.session, 2);
    EXPECT_EQ(c.max_queue, 9);
    EXPECT_EQ(c.pack_after, 0);
    EXPECT_TRUE(c.skip_while_busy);
    EXPECT_DOUBLE_EQ(c.cpu_share, 0.4);
    EXPECT_EQ(c.cpu_budget, "background");
    EXPECT_DOUBLE_EQ(c.max_queue_mb, 64.0);
    EXPECT_DOUBLE_EQ(c.maintenance.voxel_size, 0.3);
    ASSERT_TRUE(c.maintenance.change.sigma.has_value());
    EXPECT_DOUBLE_EQ(*c.maintenance.change.sigma, 2.5);
    EXPECT_TRUE(c.maintenance.change.voxel_level);
    EXPECT_DOUBLE_EQ(c.maintenance.ground.height, 0.4);
    // Untouched keys: the core's defaults.
    const MaintenanceConfig d;
    EXPECT_DOUBLE_EQ(c.maintenance.max_range, d.max_range);
    EXPECT_EQ(c.maintenance.change.min_views, d.change.min_views);
    // The time-dependent keys not given stay unset: derived from the data.
    EXPECT_FALSE(c.maintenance.change.min_views.has_value());
    EXPECT_FALSE(c.maintenance.change.static_span.has_value());
    EXPECT_FALSE(c.maintenance.view_spacing.has_value());

    runtime::Parameters none = params_of("{}");
    const MaintenanceComponentConfig n = load_maintenance_params(none);
    EXPECT_EQ(n.input, PoseInput::kOdometry);
    EXPECT_TRUE(n.output_dir.empty());
    EXPECT_TRUE(n.map_file.empty());
    EXPECT_EQ(n.session, -1);
    EXPECT_DOUBLE_EQ(n.cpu_share, 1.0);        // not paced
    EXPECT_TRUE(n.cpu_budget.empty());         // its own
    EXPECT_DOUBLE_EQ(n.max_queue_mb, 128.0);   // a VLP-32C's 300 scans fit
    EXPECT_DOUBLE_EQ(n.paging_radius, 100.0);  // paged: the neighbourhood in memory
    EXPECT_TRUE(n.paging_dir.empty());

    runtime::Parameters paged = params_of("paging_radius: 0\npaging_dir: /tmp/pages\n");
    const MaintenanceComponentConfig g = load_maintenance_params(paged);
    EXPECT_NO_THROW(paged.check_all_used());
    EXPECT_DOUBLE_EQ(g.paging_radius, 0.0);
    EXPECT_EQ(g.paging_dir, "/tmp/pages");
    EXPECT_DOUBLE_EQ(n.views.distance, 0.0);  // every scan

    runtime::Parameters spaced =
        params_of("view_distance: 0.4\nview_angle: 5\nview_interval_s: 2\n");
    const MaintenanceComponentConfig v = load_maintenance_params(spaced);
    EXPECT_NO_THROW(spaced.check_all_used());
    EXPECT_DOUBLE_EQ(v.views.distance, 0.4);
    EXPECT_DOUBLE_EQ(v.views.angle_deg, 5.0);
    EXPECT_DOUBLE_EQ(v.views.interval_s, 2.0);
}

TEST(MaintenanceParams, ABadParameterIsOneLineNamingFileLineAndKey) {
    EXPECT_EQ(error_of("input: lidar"),
              "test.yaml:1: maintenance.input: expected odometry, pose or pose_with_covariance, "
              "got 'lidar'");
    EXPECT_EQ(error_of("maintain_every_s: -1"),
              "test.yaml:1: maintenance.maintain_every_s: must be >= 0 (0: only at shutdown)");
    EXPECT_EQ(error_of("maintain_every_s: often"),
              "test.yaml:1: maintenance.maintain_every_s: expected a number, got 'often'");
    EXPECT_EQ(error_of("a: 1\nvoxel_size: 0").rfind("test.yaml:2: maintenance.voxel_size: ", 0), 0u)
        << error_of("a: 1\nvoxel_size: 0");
    EXPECT_EQ(error_of("change: {sigmaa: 2}")
                  .rfind("test.yaml:1: maintenance.change.sigmaa: unknown parameter", 0),
              0u)
        << error_of("change: {sigmaa: 2}");
    // A rule across fields.
    EXPECT_NE(error_of("change: {gone_hit_fraction: 0.9, new_hit_fraction: 0.5}")
                  .find("maintenance.change.gone_hit_fraction: must be below"),
              std::string::npos);
    // A site (site_dir) or a file (map_file), not both; a version needs a site.
    EXPECT_EQ(error_of("map_file: /tmp/m.bin\nsite_dir: /tmp/site"),
              "test.yaml:1: maintenance.map_file: give either map_file or site_dir, not both");
    EXPECT_EQ(error_of("cpu_share: 0"),
              "test.yaml:1: maintenance.cpu_share: must be in (0, 1] (1: not paced)");
    EXPECT_EQ(error_of("max_queue_mb: -1"),
              "test.yaml:1: maintenance.max_queue_mb: must be >= 0 (0: only max_queue bounds)");
    EXPECT_EQ(error_of("paging_radius: -5"),
              "test.yaml:1: maintenance.paging_radius: must be >= 0 (0: no paging)");
    EXPECT_EQ(error_of("view_distance: -0.4"),
              "test.yaml:1: maintenance.view_distance: must be >= 0 (0: every scan)");
    EXPECT_EQ(error_of("view_interval_s: 0"),
              "test.yaml:1: maintenance.view_interval_s: must be > 0 [s]");
    EXPECT_EQ(error_of("site_version: v0003"),
              "test.yaml:1: maintenance.site_version: needs site_dir");
    // An optional key is checked when given, and named among the known keys of a misspelt one.
    EXPECT_EQ(error_of("change: {static_span: -1}")
                  .rfind("test.yaml:1: maintenance.change.static_span: must be >= 0", 0),
              0u)
        << error_of("change: {static_span: -1}");
    EXPECT_EQ(error_of("change: {min_views: many}"),
              "test.yaml:1: maintenance.change.min_views: expected an integer, got 'many'");
    EXPECT_NE(error_of("change: {static_spam: 2}").find("static_span"), std::string::npos)
        << error_of("change: {static_spam: 2}");
    for (const std::string bad : {"input: lidar", "max_queue: 0", "pack_after: -2", "session: -2",
                                  "skip_while_busy: maybe", "slot: -1"}) {
        const std::string e = error_of(bad);
        EXPECT_FALSE(e.empty()) << bad;
        EXPECT_EQ(e.find('\n'), std::string::npos) << e;
    }
}

}  // namespace
}  // namespace ltm::maintenance
