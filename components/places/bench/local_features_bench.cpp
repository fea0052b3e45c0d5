// Local ScanContext++ features on real data: how often RANSAC (Umeyama) on the matched samples
// finds the pose, and how long extraction and matching take (one core).
//   local_features_bench kitti KITTI_DIR [options]  each frame, turned by a random yaw and shifted
//       up to 5 m, against the voxel centres (0.6 m) of the other frames of its snippet
//   local_features_bench hku HKU_DIR [options]  session 2's scan j of each cross-session pair
//       against session 1's scans i-5..i+5 (voxel centres), both levelled by their ground
//   local_features_bench speed [options]  matching time of 200 x 1000 synthetic-scene samples
// Options: --spacing M --query-spacing M --radius M --rings N --sectors N --max-height M
//   --empty-cost C --unseen-cost C --candidates N --per-query N --inlier M --max-samples N
//   --min-points N --min-bins N --max-range M --target-radius M --target-max-samples N
//   --voxel M --ground-cell M --ground-window M --no-level --ground-level --no-refine -v
#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "common/core/kitti_io.hpp"
#include "common/core/pcl_cloud_io.hpp"
#include "common/core/trajectory_io.hpp"
#include "places/core/local_feature_matching.hpp"
#include "places/core/local_features.hpp"
#include "registration/core/ransac_alignment.hpp"
#include "registration/core/se3.hpp"
#include "registration/core/test_scenes.hpp"

namespace {

using namespace ltm;
using Eigen::Isometry3d;
using Eigen::Matrix3d;
using Eigen::Vector3d;
using Eigen::Vector3f;
using Clock = std::chrono::steady_clock;

constexpr double kDeg = M_PI / 180.0;

struct Options {
    places::LocalFeatureConfig query, target;
    places::LocalFeatureMatchConfig match;
    registration::RansacAlignmentConfig ransac;
    double target_radius = 40.0;
    bool verbose = false;
    bool level = true;          // hku: level each session's world by its trajectory plane
    bool ground_level = false;  // level each side by its ground samples before matching
    bool refine = true;         // the matches' refined target positions (else the samples')
};

double ms_since(Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

std::vector<Vector3f> transformed(const std::vector<Vector3f>& points, const Isometry3d& T) {
    std::vector<Vector3f> out;
    out.reserve(points.size());
    for (const Vector3f& p : points) out.push_back((T * p.cast<double>()).cast<float>());
    return out;
}

// Voxel centroids (the stand-in for a map's voxel centres).
std::vector<Vector3f> voxelised(const std::vector<Vector3f>& points, double voxel) {
    std::vector<std::pair<Eigen::Vector3i, Vector3f>> keyed;
    keyed.reserve(points.size());
    for (const Vector3f& p : points) {
        if (!p.allFinite()) continue;
        keyed.push_back({(p.cast<double>() / voxel).array().floor().cast<int>(), p});
    }
    const auto less = [](const auto& a, const auto& b) {
        return std::lexicographical_compare(a.first.data(), a.first.data() + 3, b.first.data(),
                                            b.first.data() + 3);
    };
    std::sort(keyed.begin(), keyed.end(), less);
    std::vector<Vector3f> out;
    for (std::size_t i = 0; i < keyed.size();) {
        std::size_t j = i;
        Eigen::Vector3d sum = Eigen::Vector3d::Zero();
        while (j < keyed.size() && keyed[j].first == keyed[i].first)
            sum += keyed[j++].second.cast<double>();
        out.push_back((sum / double(j - i)).cast<float>());
        i = j;
    }
    return out;
}

struct Trial {
    bool found = false, right = false, near = false;  // near: within 2 m / 5 deg (ICP's reach)
    std::size_t inliers = 0, matches = 0, query_samples = 0, target_samples = 0;
    double t_err = 0.0, r_err = 0.0, yaw_err = 0.0, extract_ms = 0.0, match_ms = 0.0;
};

// The rotation that makes the plane through the ground samples level (identity when fewer than
// six samples); two rounds drop samples more than 0.3 m off the plane.
Matrix3d ground_levelling(const std::vector<Vector3d>& samples) {
    std::vector<Vector3d> used = samples;
    Vector3d n = Vector3d::UnitZ();
    for (int round = 0; round < 3 && used.size() >= 6; ++round) {
        Eigen::MatrixXd A(used.size(), 3);
        Eigen::VectorXd z(used.size());
        for (std::size_t k = 0; k < used.size(); ++k) {
            A.row(Eigen::Index(k)) << used[k].x(), used[k].y(), 1.0;
            z[Eigen::Index(k)] = used[k].z();
        }
        const Eigen::Vector3d abd = A.colPivHouseholderQr().solve(z);
        n = Vector3d(-abd[0], -abd[1], 1.0).normalized();
        std::vector<Vector3d> kept;
        for (const Vector3d& p : used) {
            if (std::abs(p.z() - (abd[0] * p.x() + abd[1] * p.y() + abd[2])) < 0.3) {
                kept.push_back(p);
            }
        }
        used = kept;
    }
    return Eigen::Quaterniond::FromTwoVectors(n, Vector3d::UnitZ()).toRotationMatrix();
}

Trial run_trial(const std::vector<Vector3f>& query_input, const std::vector<Vector3f>& target_input,
                const Isometry3d& T_input, const Options& o) {
    Trial t;
    std::vector<Vector3f> query_points = query_input, target_points = target_input;
    Isometry3d T_target_query = T_input;
    if (o.ground_level) {
        // Each side levelled by its own ground samples (a stand-in for a poor gravity estimate).
        Isometry3d Lq = Isometry3d::Identity(), Lt = Isometry3d::Identity();
        Lq.linear() = ground_levelling(places::make_local_features(query_input, o.query).positions);
        Lt.linear() = ground_levelling(
            places::make_local_features(target_input, o.target, Vector3d::Zero(), o.target_radius)
                .positions);
        query_points = transformed(query_input, Lq);
        target_points = transformed(target_input, Lt);
        T_target_query = Lt * T_input * Lq.inverse();
    }
    auto t0 = Clock::now();
    const places::LocalFeatures q = places::make_local_features(query_points, o.query);
    t.extract_ms = ms_since(t0);
    const places::LocalFeatures g =
        places::make_local_features(target_points, o.target, Vector3d::Zero(), o.target_radius);
    t0 = Clock::now();
    const auto matches = places::match_local_features(q, g, o.match);
    t.match_ms = ms_since(t0);
    t.query_samples = q.size();
    t.target_samples = g.size();
    t.matches = matches.size();
    std::vector<Vector3d> src, dst;
    for (const auto& m : matches) {
        src.push_back(q.positions[m.query]);
        dst.push_back(o.refine ? m.target_position : g.positions[m.target]);
    }
    const auto r = registration::ransac_align(src, dst, o.ransac);
    if (!r) return t;
    t.found = true;
    t.inliers = r->inliers.size();
    const Isometry3d e = T_target_query.inverse() * r->T_target_source;
    t.t_err = e.translation().norm();
    t.r_err = registration::rotation_angle(e) / kDeg;
    t.yaw_err = std::atan2(e.linear()(1, 0), e.linear()(0, 0)) / kDeg;
    t.right = t.t_err < 0.5 && t.r_err < 2.0;
    t.near = t.t_err < 2.0 && t.r_err < 5.0;
    return t;
}

struct Tally {
    int trials = 0, right = 0, near = 0, found_wrong = 0;
    std::vector<double> extract_ms, match_ms, right_inliers, wrong_inliers;
    void add(const Trial& t) {
        ++trials;
        right += t.right;
        near += t.near;
        found_wrong += t.found && !t.near;
        extract_ms.push_back(t.extract_ms);
        match_ms.push_back(t.match_ms);
        if (t.found) (t.near ? right_inliers : wrong_inliers).push_back(double(t.inliers));
    }
    static double median(std::vector<double> v) {
        if (v.empty()) return 0.0;
        std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
        return v[v.size() / 2];
    }
    static double max(const std::vector<double>& v) {
        return v.empty() ? 0.0 : *std::max_element(v.begin(), v.end());
    }
    void print(const char* name) const {
        std::printf(
            "%s: %d/%d right (0.5 m / 2 deg), %d near (2 m / 5 deg), %d answered wrong (not "
            "near); inliers median right %.0f, wrong %.0f (max %.0f); extract %.1f ms median, "
            "match %.1f ms median (max %.1f)\n",
            name, right, trials, near, found_wrong, median(right_inliers), median(wrong_inliers),
            max(wrong_inliers), median(extract_ms), median(match_ms), max(match_ms));
    }
};

void print_trial(const char* what, const Trial& t) {
    std::printf("%s q %zu t %zu m %zu %s inl %zu err %.2f m %.2f deg (yaw %.2f) (%.1f + %.1f ms)\n",
                what, t.query_samples, t.target_samples, t.matches,
                t.right ? "RIGHT" : (t.near ? "near" : (t.found ? "wrong" : "none")), t.inliers,
                t.t_err, t.r_err, t.yaw_err, t.extract_ms, t.match_ms);
}

int run_kitti(const std::string& dir, const Options& o) {
    Tally tally;
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> yaw(-180.0, 180.0), shift(-5.0, 5.0);
    for (const auto& entry : std::filesystem::directory_iterator(dir + "/sequences")) {
        const std::string seq = entry.path().string();
        if (!std::filesystem::exists(seq + "/velodyne")) continue;
        const auto files = common::list_kitti_scans(seq);
        const auto Tr = common::read_kitti_calib_tr(seq + "/calib.txt");
        const auto poses = common::camera_to_lidar_poses(
            common::read_kitti_poses(seq + "/poses_semantickitti.txt"), Tr);
        std::vector<std::vector<Vector3f>> scans;
        for (const auto& f : files) scans.push_back(common::read_kitti_bin(f).points);
        for (std::size_t i = 0; i < scans.size(); ++i) {
            std::vector<Vector3f> merged;
            for (std::size_t k = 0; k < scans.size(); ++k) {
                if (k == i) continue;
                const auto s = transformed(scans[k], poses[i].inverse() * poses[k]);
                merged.insert(merged.end(), s.begin(), s.end());
            }
            const std::vector<Vector3f> map = voxelised(merged, 0.6);
            // The query frame: the scan turned and shifted (T_target_query its pose in frame i).
            const Isometry3d T_target_query =
                registration::test::make_pose(shift(rng), shift(rng), 0.0, 0, 0, yaw(rng));
            const Trial t =
                run_trial(transformed(scans[i], T_target_query.inverse()), map, T_target_query, o);
            tally.add(t);
            if (o.verbose) {
                const std::string what = entry.path().filename().string() + "/" + std::to_string(i);
                print_trial(what.c_str(), t);
            }
        }
    }
    tally.print("kitti");
    return 0;
}

// The rotation that levels a session's world frame: the normal of the plane fitted to its
// trajectory (a robot driving on a flat campus), with the fit's rms residual.
Matrix3d levelling(const common::PoseList& poses, double* rms) {
    Eigen::MatrixXd A(poses.size(), 3);
    Eigen::VectorXd z(poses.size());
    for (std::size_t k = 0; k < poses.size(); ++k) {
        const Vector3d t = poses[k].translation();
        A.row(Eigen::Index(k)) << t.x(), t.y(), 1.0;
        z[Eigen::Index(k)] = t.z();
    }
    const Eigen::Vector3d abd = A.colPivHouseholderQr().solve(z);
    *rms = std::sqrt((A * abd - z).squaredNorm() / double(poses.size()));
    const Vector3d n = Vector3d(-abd[0], -abd[1], 1.0).normalized();
    return Eigen::Quaterniond::FromTwoVectors(n, Vector3d::UnitZ()).toRotationMatrix();
}

struct Session {
    std::vector<std::vector<Vector3f>> scans;
    common::PoseList poses;
    Matrix3d level = Matrix3d::Identity();
};

Session load_session(const std::string& dir, bool level) {
    Session s;
    s.poses = common::read_kitti_poses(dir + "/odom_poses.txt");
    std::vector<Vector3f> world;
    for (std::size_t i = 0; i < s.poses.size(); ++i) {
        char name[32];
        std::snprintf(name, sizeof name, "/Scans/%06zu.pcd", i);
        s.scans.push_back(common::load_cloud_file(dir + name).points);
        const auto w = transformed(s.scans.back(), s.poses[i]);
        world.insert(world.end(), w.begin(), w.end());
    }
    double rms = 0.0;
    s.level = level ? levelling(s.poses, &rms) : Matrix3d::Identity();
    std::printf("%s: levelled by %.2f deg (trajectory plane, rms %.2f m)\n", dir.c_str(),
                Eigen::AngleAxisd(s.level).angle() / kDeg, rms);
    return s;
}

int run_hku(const std::string& dir, const Options& o) {
    const Session s1 = load_session(dir + "/session1", o.level),
                  s2 = load_session(dir + "/session2", o.level);
    std::ifstream in(dir + "/verified_pairs.txt");
    std::string line;
    Tally verified, others;
    while (std::getline(in, line)) {
        std::istringstream ls(line);
        std::string kind, sa, sb;
        int i = 0, j = 0, ok = 0;
        double skip = 0.0;
        if (!(ls >> kind >> sa >> i >> sb >> j) || kind != "cross") continue;
        for (int k = 0; k < 7; ++k) ls >> skip;
        ls >> ok;
        Eigen::Matrix<double, 3, 4> m;
        for (int r = 0; r < 3; ++r) {
            for (int c = 0; c < 4; ++c) ls >> m(r, c);
        }
        Isometry3d T_A_B = Isometry3d::Identity();
        T_A_B.matrix().topRows<3>() = m;
        // Target frame: session 1's levelled world, moved to scan i's position.
        const Isometry3d& P_i = s1.poses[std::size_t(i)];
        Isometry3d T_t_w = Isometry3d::Identity();
        T_t_w.linear() = s1.level;
        T_t_w.translation() = -(s1.level * P_i.translation());
        std::vector<Vector3f> merged;
        for (int k = std::max(0, i - 5); k <= std::min(int(s1.scans.size()) - 1, i + 5); ++k) {
            const auto w = transformed(s1.scans[std::size_t(k)], T_t_w * s1.poses[std::size_t(k)]);
            merged.insert(merged.end(), w.begin(), w.end());
        }
        // Query frame: scan j levelled (rotation only).
        Isometry3d M_q = Isometry3d::Identity();
        M_q.linear() = s2.level * s2.poses[std::size_t(j)].linear();
        const Isometry3d T_target_query = (T_t_w * P_i) * T_A_B * M_q.inverse();
        const Trial t = run_trial(transformed(s2.scans[std::size_t(j)], M_q),
                                  voxelised(merged, 0.6), T_target_query, o);
        (ok ? verified : others).add(t);
        if (o.verbose) {
            const std::string what = "s1 " + std::to_string(i) + " s2 " + std::to_string(j) +
                                     (ok ? " verified" : " other");
            print_trial(what.c_str(), t);
        }
    }
    verified.print("hku verified cross pairs");
    others.print("hku other cross pairs");
    return 0;
}

int run_speed(const Options& o) {
    // Extraction: a full KITTI scan (the shared data when present, else the repository's
    // quarter-density fixture). Matching: up to 200 query samples of one simulated street scan
    // against up to 1000 samples of a map of the street (1.5 m lattices to get that many).
    std::string scan_file =
        std::string(LTM_SOURCE_DIR) + "/../shared/data/kitti/sequences/00/velodyne/000000.bin";
    if (!std::filesystem::exists(scan_file)) {
        scan_file =
            std::string(LTM_SOURCE_DIR) + "/tests/fixtures/kitti00_mini/velodyne/000000.bin";
    }
    const std::vector<Vector3f> kitti = common::read_kitti_bin(scan_file).points;
    double extract = 1e9;
    std::size_t kitti_samples = 0;
    for (int rep = 0; rep < 5; ++rep) {
        const auto t0 = Clock::now();
        kitti_samples = places::make_local_features(kitti, o.query).size();
        extract = std::min(extract, ms_since(t0));
    }
    std::printf("extract: %s, %zu points -> %zu samples in %.1f ms (best of 5)\n",
                scan_file.c_str(), kitti.size(), kitti_samples, extract);

    const registration::test::Scene scene = registration::test::street_scene();
    registration::test::ScanPattern pattern;
    pattern.rings = 64;
    pattern.azimuths = 1800;
    pattern.max_range = 80.0;
    std::vector<Vector3f> map;
    for (double x = 20.0; x <= 280.0; x += 10.0) {
        const Isometry3d T = registration::test::make_pose(x, 0.0, 1.8, 0, 0, 0);
        const auto s =
            transformed(registration::test::scan_scene(scene, pattern, T, T, 1).points, T);
        map.insert(map.end(), s.begin(), s.end());
    }
    map = voxelised(map, 0.6);
    places::LocalFeatureConfig tc = o.target, qc = o.query;
    tc.sample_spacing = qc.sample_spacing = 1.5;
    tc.max_samples = 1000;
    const auto target = places::make_local_features(map, tc, Vector3d(150, 0, 0), 140.0);
    const Isometry3d T = registration::test::make_pose(100.0, 0.5, 1.8, 0, 0, 40.0);
    const auto q = places::make_local_features(
        registration::test::scan_scene(scene, pattern, T, T, 2).points, qc);
    double match = 1e9;
    std::size_t n = 0;
    for (int rep = 0; rep < 5; ++rep) {
        const auto t0 = Clock::now();
        n = places::match_local_features(q, target, o.match).size();
        match = std::min(match, ms_since(t0));
    }
    std::printf(
        "match: %zu x %zu samples, %d key candidates a query, in %.1f ms (best of 5; %zu "
        "matches)\n",
        q.size(), target.size(), o.match.key_candidates, match, n);
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: local_features_bench kitti DIR | hku DIR | speed [options]\n");
        return 2;
    }
    const std::string mode = argv[1];
    std::string dir;
    int a = 2;
    if (mode != "speed") {
        if (argc < 3) {
            std::fprintf(stderr, "local_features_bench %s: a data folder is needed\n",
                         mode.c_str());
            return 2;
        }
        dir = argv[2];
        a = 3;
    }
    Options o;
    o.target.max_samples = 4000;
    o.ransac.inlier_distance = 0.5 * o.target.sample_spacing;
    double query_spacing = -1.0;
    for (; a < argc; ++a) {
        const std::string k = argv[a];
        if (k == "-v") {
            o.verbose = true;
            continue;
        }
        if (k == "--no-level") {
            o.level = false;
            continue;
        }
        if (k == "--no-refine") {
            o.refine = false;
            continue;
        }
        if (k == "--ground-level") {
            o.ground_level = true;
            continue;
        }
        if (a + 1 >= argc) {
            std::fprintf(stderr, "local_features_bench: %s needs a value\n", k.c_str());
            return 2;
        }
        const double v = std::atof(argv[++a]);
        if (k == "--spacing") {
            o.target.sample_spacing = v;
            o.ransac.inlier_distance = 0.5 * v;
        } else if (k == "--query-spacing") {
            query_spacing = v;
        } else if (k == "--radius") {
            o.query.radius = o.target.radius = v;
        } else if (k == "--rings") {
            o.query.rings = o.target.rings = int(v);
        } else if (k == "--sectors") {
            o.query.sectors = o.target.sectors = int(v);
        } else if (k == "--max-height") {
            o.query.max_height = o.target.max_height = v;
        } else if (k == "--empty-cost") {
            o.match.empty_bin_cost = v;
        } else if (k == "--unseen-cost") {
            o.match.unseen_bin_cost = v;
        } else if (k == "--candidates") {
            o.match.key_candidates = int(v);
        } else if (k == "--per-query") {
            o.match.per_query = int(v);
        } else if (k == "--inlier") {
            o.ransac.inlier_distance = v;
        } else if (k == "--max-samples") {
            o.query.max_samples = int(v);
        } else if (k == "--min-points") {
            o.query.min_points_per_descriptor = o.target.min_points_per_descriptor = int(v);
        } else if (k == "--min-bins") {
            o.query.min_occupied_bins = o.target.min_occupied_bins = int(v);
        } else if (k == "--max-range") {
            o.query.max_range = v;
        } else if (k == "--target-max-samples") {
            o.target.max_samples = int(v);
        } else if (k == "--ground-cell") {
            o.query.ground_cell = o.target.ground_cell = v;
        } else if (k == "--ground-window") {
            o.query.ground_window = o.target.ground_window = v;
        } else if (k == "--voxel") {
            o.query.voxel_size = o.target.voxel_size = v;
        } else if (k == "--target-radius") {
            o.target_radius = v;
        } else {
            std::fprintf(stderr, "local_features_bench: unknown option %s\n", k.c_str());
            return 2;
        }
    }
    o.query.sample_spacing = query_spacing > 0.0 ? query_spacing : o.target.sample_spacing;
    try {
        if (mode == "kitti") return run_kitti(dir, o);
        if (mode == "hku") return run_hku(dir, o);
        if (mode == "speed") return run_speed(o);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "local_features_bench: %s\n", e.what());
        return 1;
    }
    std::fprintf(stderr, "local_features_bench: unknown mode %s\n", mode.c_str());
    return 2;
}
