// SITE/anchor.yaml: a transform fitted to surveyed points (Umeyama without scale) recovers the
// true one; too few points or points on one line are refused in one line; the file round-trips
// and a damaged one is refused naming the line.
#include "map/core/site_anchor.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>

#include "common/core/io_error.hpp"

namespace ltm::map {
namespace {

namespace fs = std::filesystem;

fs::path fresh(const std::string& name) {
    const fs::path p = fs::path(LTM_BINARY_DIR) / "site_test" / name;
    fs::remove_all(p);
    fs::create_directories(p);
    return p;
}

std::string error_of(const std::function<void()>& f) {
    try {
        f();
    } catch (const std::exception& e) {
        return e.what();
    }
    return "(no error)";
}

TEST(SiteAnchor, SurveyedPointsRecoverTheTransform) {
    const SiteAnchor truth = anchor_from_transform({512300.0, 5403100.0, 212.5}, 1.0, -2.0, 73.0);
    std::mt19937 rng(5);
    std::normal_distribution<double> noise(0.0, 0.003);  // 3 mm survey noise
    std::vector<Eigen::Vector3d> map, site;
    for (const Eigen::Vector3d& p : {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(80, 5, 1),
                                     Eigen::Vector3d(40, 60, -2), Eigen::Vector3d(-30, 20, 4)}) {
        map.push_back(p);
        site.push_back(truth.T_site_map * p + Eigen::Vector3d(noise(rng), noise(rng), noise(rng)));
    }
    const SiteAnchor fit = fit_anchor(map, site);
    EXPECT_EQ(fit.source, "points");
    EXPECT_EQ(fit.points, 4u);
    EXPECT_LT((fit.T_site_map.translation() - truth.T_site_map.translation()).norm(), 0.02);
    EXPECT_LT(Eigen::AngleAxisd(fit.T_site_map.rotation().transpose() * truth.T_site_map.rotation())
                  .angle(),
              1e-3);
    EXPECT_GT(fit.rms_m, 0.0);
    EXPECT_LT(fit.rms_m, 0.01);
    EXPECT_LE(fit.rms_m, fit.max_m);
}

TEST(SiteAnchor, TooFewPointsOrPointsOnALineAreRefused) {
    const std::vector<Eigen::Vector3d> two = {{0, 0, 0}, {1, 0, 0}};
    EXPECT_NE(error_of([&] { fit_anchor(two, two); }).find("2 surveyed points; at least 3"),
              std::string::npos);
    const std::vector<Eigen::Vector3d> line = {{0, 0, 0}, {10, 10, 0}, {20, 20, 0}, {35, 35, 0}};
    EXPECT_NE(error_of([&] { fit_anchor(line, line); }).find("on one line"), std::string::npos);
}

TEST(SiteAnchor, FileRoundTripAndDamage) {
    const fs::path site = fresh("anchor");
    EXPECT_FALSE(read_anchor(site.string()).has_value());
    SiteAnchor a = anchor_from_transform({10.0, -4.0, 0.5}, 0.0, 0.0, 90.0);
    write_anchor(site.string(), a);
    const std::optional<SiteAnchor> r = read_anchor(site.string());
    ASSERT_TRUE(r.has_value());
    EXPECT_TRUE(r->T_site_map.isApprox(a.T_site_map, 1e-9));
    EXPECT_TRUE(
        (r->T_site_map * Eigen::Vector3d(1, 0, 0)).isApprox(Eigen::Vector3d(10, -3, 0.5), 1e-9));
    EXPECT_EQ(r->source, "transform");
    std::ofstream(anchor_file(site.string()), std::ios::app) << "scale: 2\n";
    const std::string e = error_of([&] { read_anchor(site.string()); });
    EXPECT_NE(e.find("line 8"), std::string::npos) << e;
    EXPECT_NE(e.find("unknown key 'scale'"), std::string::npos) << e;
    EXPECT_EQ(e.find('\n'), std::string::npos);
}

TEST(SiteAnchor, SurveyFileIsReadAndABadLineNamed) {
    const fs::path dir = fresh("survey");
    std::ofstream(dir / "points.txt") << "# map xyz  site xyz\n0 0 0  100 200 10\n\n"
                                         "10 0 0 110 200 10  # a comment\n0 10 0 100 210 10\n";
    std::vector<Eigen::Vector3d> map, site;
    read_survey_points((dir / "points.txt").string(), &map, &site);
    ASSERT_EQ(map.size(), 3u);
    const SiteAnchor a = fit_anchor(map, site);
    EXPECT_TRUE(a.T_site_map.translation().isApprox(Eigen::Vector3d(100, 200, 10), 1e-9));
    EXPECT_LT(a.max_m, 1e-9);
    std::ofstream(dir / "bad.txt") << "0 0 0 1 1 1\n0 0 0 1 1\n";
    map.clear();
    site.clear();
    const std::string e =
        error_of([&] { read_survey_points((dir / "bad.txt").string(), &map, &site); });
    EXPECT_NE(e.find("line 2 at byte 12: expected 6 numbers"), std::string::npos) << e;
}

}  // namespace
}  // namespace ltm::map
