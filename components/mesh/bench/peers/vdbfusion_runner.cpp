// VDBFusion (github.com/PRBonn/vdbfusion, MIT licence) run over the scan folders ltm_bench_mesh
// reads, at the same poses, as a side-by-side peer of ltm's dense mesh. This file is ltm's own
// code: it only links VDBFusion's C++ core (vdbfusion::VDBVolume), built from a snapshot of its
// repository by vdbfusion.sh; it is not part of ltm's build.
//
// What it does is what VDBFusion's examples/python/vdbfusion_pipeline.py does with its KITTI
// dataset (examples/python/datasets/kitti_odometry.py), for each kept scan:
//   points (float32 x y z intensity) -> [--correct-scan: the HDL-64E 0.205 deg vertical-angle
//   correction] -> keep min_range <= |p| <= max_range -> move by the LiDAR pose T_world_lidar ->
//   VDBVolume::Integrate(points, origin = the pose's translation, weight 1 for every sample)
// and at the end VDBVolume::ExtractTriangleMesh(fill_holes, min_weight).
// Defaults: examples/python/config/kitti.yaml (voxel_size 0.1, sdf_trunc 0.3, space_carving off,
// fill_holes off, min_weight 5, min_range 2.5, max_range 120). correct_scan is on there; here it
// is off by default (--correct-scan 1 turns it on), so that VDBFusion integrates exactly the points
// ltm integrates and the held-out points are scored without it.
//
// Time: only the call to Integrate is timed a scan (as the Python pipeline's perf_counter around
// integrate), wall clock; meshing is the call to ExtractTriangleMesh. VDBFusion's Integrate and
// ExtractTriangleMesh are single-threaded loops; a tbb::global_control keeps anything OpenVDB might
// run on TBB to one thread too, for a one-thread comparison with ltm.
//
// Scans: DIR/velodyne/*.bin or DIR/*.bin in name order (ltm's ScanFolder's order), scan i at line
// i of the poses; --frames A:B, --every K, --offset O keep scans A+O, A+O+K, ... below B, as
// ltm_bench_mesh does. Output: the mesh as a binary PLY, and a summary on stdout.
#include <openvdb/openvdb.h>
#include <sys/resource.h>
#include <tbb/global_control.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "vdbfusion/VDBVolume.h"

namespace fs = std::filesystem;

namespace {

struct Args {
    std::string dir;
    std::string poses;
    std::string calib;  // empty: the poses are LiDAR poses
    std::string out;
    std::size_t first = 0;
    std::size_t last = 0;  // 0: to the last scan
    std::size_t every = 1;
    std::size_t offset = 0;
    double voxel = 0.1;        // [m] voxel_size
    double trunc = 0.3;        // [m] sdf_trunc
    double min_range = 2.5;    // [m]
    double max_range = 120.0;  // [m]
    double min_weight = 5.0;
    bool space_carving = false;
    bool fill_holes = false;
    bool correct_scan = false;
};

// One line for the user; main prints it and exits 1.
struct UserError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

const char* const kUsage =
    "usage: vdbfusion_runner DIR --poses POSES.txt [--calib CALIB.txt] [--frames A:B]\n"
    "         [--every K] [--offset O] [--voxel 0.1] [--trunc 0.3] [--space-carving 0|1]\n"
    "         [--min-range 2.5] [--max-range 120] [--min-weight 5] [--fill-holes 0|1]\n"
    "         [--correct-scan 0|1] --out MESH.ply\n"
    "  DIR: KITTI layout (DIR/velodyne/*.bin or DIR/*.bin); scan i is at line i of POSES\n"
    "  --poses FILE      KITTI-format poses T_world_lidar (with --calib: camera poses)\n"
    "  --calib FILE      KITTI calib.txt whose Tr turns camera poses into LiDAR poses\n"
    "  --frames A:B      scans A..B-1 (A: or :B allowed)\n"
    "  --every K, --offset O  integrate scans A+O, A+O+K, ... (the others are skipped)\n"
    "  --correct-scan 1  the KITTI HDL-64E 0.205 deg correction of VDBFusion's KITTI loader\n"
    "Defaults: VDBFusion's examples/python/config/kitti.yaml (correct_scan off here). One "
    "thread.\n";

double parse_number(const std::string& option, const std::string& text) {
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (text.empty() || *end != '\0' || !std::isfinite(v))
        throw UserError(option + ": expected a number, got '" + text + "'");
    return v;
}

std::size_t parse_count(const std::string& option, const std::string& text, bool allow_zero) {
    const double v = parse_number(option, text);
    if (v != std::floor(v) || v < (allow_zero ? 0.0 : 1.0) || v > 1e12)
        throw UserError(option + ": expected a " + (allow_zero ? "non-negative" : "positive") +
                        " integer, got '" + text + "'");
    return std::size_t(v);
}

bool parse_flag(const std::string& option, const std::string& text) {
    if (text == "0" || text == "false") return false;
    if (text == "1" || text == "true") return true;
    throw UserError(option + ": expected 0 or 1, got '" + text + "'");
}

// Returns false after printing the usage (--help).
bool parse_args(int argc, char** argv, Args& a) {
    for (int i = 1; i < argc; ++i) {
        const std::string s = argv[i];
        if (s == "-h" || s == "--help") {
            std::cout << kUsage;
            return false;
        }
        if (s.empty() || s[0] != '-') {
            if (!a.dir.empty())
                throw UserError("one folder only, got '" + a.dir + "' and '" + s + "'");
            a.dir = s;
            continue;
        }
        if (i + 1 >= argc) throw UserError(s + ": needs a value");
        const std::string v = argv[++i];
        if (s == "--poses") {
            a.poses = v;
        } else if (s == "--calib") {
            a.calib = v;
        } else if (s == "--out") {
            a.out = v;
        } else if (s == "--frames") {
            const std::size_t colon = v.find(':');
            if (colon == std::string::npos)
                throw UserError("--frames: expected A:B, got '" + v + "'");
            const std::string lo = v.substr(0, colon), hi = v.substr(colon + 1);
            a.first = lo.empty() ? 0 : parse_count(s, lo, true);
            a.last = hi.empty() ? 0 : parse_count(s, hi, false);
            if (a.last != 0 && a.last <= a.first)
                throw UserError("--frames: empty range '" + v + "'");
        } else if (s == "--every") {
            a.every = parse_count(s, v, false);
        } else if (s == "--offset") {
            a.offset = parse_count(s, v, true);
        } else if (s == "--voxel") {
            a.voxel = parse_number(s, v);
        } else if (s == "--trunc") {
            a.trunc = parse_number(s, v);
        } else if (s == "--min-range") {
            a.min_range = parse_number(s, v);
        } else if (s == "--max-range") {
            a.max_range = parse_number(s, v);
        } else if (s == "--min-weight") {
            a.min_weight = parse_number(s, v);
        } else if (s == "--space-carving") {
            a.space_carving = parse_flag(s, v);
        } else if (s == "--fill-holes") {
            a.fill_holes = parse_flag(s, v);
        } else if (s == "--correct-scan") {
            a.correct_scan = parse_flag(s, v);
        } else {
            throw UserError("unknown option '" + s + "' (--help)");
        }
    }
    if (a.dir.empty()) throw UserError("no scan folder given (--help)");
    if (a.poses.empty()) throw UserError("--poses is required");
    if (a.out.empty()) throw UserError("--out is required");
    if (a.offset >= a.every) throw UserError("--offset must be below --every");
    if (a.voxel <= 0.0 || a.trunc <= 0.0) throw UserError("--voxel and --trunc must be positive");
    if (a.min_range < 0.0 || a.max_range <= a.min_range)
        throw UserError("--min-range and --max-range: need 0 <= min < max");
    return true;
}

std::vector<std::string> scan_files(const std::string& path) {
    std::vector<std::string> files;
    for (const fs::path& dir : {fs::path(path) / "velodyne", fs::path(path)}) {
        if (!fs::is_directory(dir)) continue;
        for (const auto& e : fs::directory_iterator(dir))
            if (e.is_regular_file() && e.path().extension() == ".bin")
                files.push_back(e.path().string());
        if (!files.empty()) break;
    }
    if (files.empty()) throw UserError(path + ": no scans (expected velodyne/*.bin or *.bin)");
    std::sort(files.begin(), files.end());
    return files;
}

// Lines of 12 numbers (a row-major 3x4 matrix); blank lines are skipped.
std::vector<Eigen::Matrix4d> read_poses(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw UserError(path + ": cannot read");
    std::vector<Eigen::Matrix4d> poses;
    std::string line;
    while (std::getline(in, line)) {
        if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
        std::istringstream ls(line);
        Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
        for (int k = 0; k < 12; ++k)
            if (!(ls >> T(k / 4, k % 4)))
                throw UserError(path + ": line " + std::to_string(poses.size() + 1) +
                                " is not 12 numbers");
        poses.push_back(T);
    }
    return poses;
}

// KITTI calib.txt: the line "Tr: 12 numbers" (T_camera_lidar).
Eigen::Matrix4d read_calib_tr(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw UserError(path + ": cannot read");
    std::string line;
    while (std::getline(in, line)) {
        if (line.rfind("Tr:", 0) != 0) continue;
        std::istringstream ls(line.substr(3));
        Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
        for (int k = 0; k < 12; ++k)
            if (!(ls >> T(k / 4, k % 4))) throw UserError(path + ": the Tr line is not 12 numbers");
        return T;
    }
    throw UserError(path + ": no 'Tr:' line");
}

std::vector<Eigen::Vector3d> read_scan(const std::string& path) {
    std::ifstream in(path, std::ios::binary | std::ios::ate);
    if (!in) throw UserError(path + ": cannot read");
    const auto bytes = static_cast<std::size_t>(in.tellg());
    if (bytes % 16 != 0) throw UserError(path + ": not float32 x y z intensity records");
    in.seekg(0);
    std::vector<float> buffer(bytes / 4);
    in.read(reinterpret_cast<char*>(buffer.data()), static_cast<std::streamsize>(bytes));
    if (!in) throw UserError(path + ": cannot read");
    std::vector<Eigen::Vector3d> points(bytes / 16);
    for (std::size_t i = 0; i < points.size(); ++i)
        points[i] = Eigen::Vector3d(buffer[4 * i], buffer[4 * i + 1], buffer[4 * i + 2]);
    return points;
}

// VDBFusion's KITTI loader (_correct_scan): each point turned by 0.205 deg about p x z.
void correct_scan(std::vector<Eigen::Vector3d>& points) {
    const double angle = 0.205 * M_PI / 180.0;
    for (Eigen::Vector3d& p : points) {
        const Eigen::Vector3d axis = p.cross(Eigen::Vector3d::UnitZ());
        const double n = axis.norm();
        if (n > 0.0) p = Eigen::AngleAxisd(angle, axis / n) * p;
    }
}

double percentile(std::vector<double> v, double q) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    const double pos = q * double(v.size() - 1);
    const std::size_t lo = std::size_t(pos);
    const std::size_t hi = std::min(lo + 1, v.size() - 1);
    return v[lo] + (pos - double(lo)) * (v[hi] - v[lo]);
}

void write_mesh(const std::string& path, const std::vector<Eigen::Vector3d>& vertices,
                const std::vector<Eigen::Vector3i>& triangles) {
    std::ofstream out(path, std::ios::binary);
    if (!out) throw UserError(path + ": cannot write");
    out << "ply\nformat binary_little_endian 1.0\ncomment VDBFusion (PRBonn/vdbfusion) mesh\n"
        << "element vertex " << vertices.size()
        << "\nproperty float x\nproperty float y\nproperty float z\n"
        << "element face " << triangles.size()
        << "\nproperty list uchar int vertex_indices\nend_header\n";
    std::vector<float> v(vertices.size() * 3);
    for (std::size_t i = 0; i < vertices.size(); ++i)
        for (int k = 0; k < 3; ++k) v[3 * i + k] = float(vertices[i][k]);
    out.write(reinterpret_cast<const char*>(v.data()), std::streamsize(v.size() * sizeof(float)));
    std::vector<char> f(triangles.size() * 13);
    for (std::size_t i = 0; i < triangles.size(); ++i) {
        const std::int32_t index[3] = {triangles[i][0], triangles[i][1], triangles[i][2]};
        f[13 * i] = 3;
        std::memcpy(&f[13 * i + 1], index, sizeof(index));
    }
    out.write(f.data(), std::streamsize(f.size()));
    if (!out) throw UserError(path + ": write failed");
}

double ms_between(std::chrono::steady_clock::time_point a,
                  std::chrono::steady_clock::time_point b) {
    return std::chrono::duration<double, std::milli>(b - a).count();
}

int run(const Args& a) {
    const std::vector<std::string> files = scan_files(a.dir);
    std::vector<Eigen::Matrix4d> poses = read_poses(a.poses);
    if (!a.calib.empty()) {  // camera poses -> LiDAR poses: Tr^-1 P Tr
        const Eigen::Matrix4d tr = read_calib_tr(a.calib);
        const Eigen::Matrix4d tr_inv = tr.inverse();
        for (Eigen::Matrix4d& P : poses) P = tr_inv * P * tr;
    }
    const std::size_t last = a.last == 0 ? files.size() : a.last;
    if (last > files.size())
        throw UserError("--frames: " + std::to_string(files.size()) + " scans in " + a.dir);
    if (a.first >= last) throw UserError("--frames: no scan in the range");
    if (poses.size() < last)
        throw UserError(a.poses + ": " + std::to_string(poses.size()) + " poses for " +
                        std::to_string(last) + " scans");

    const tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
    openvdb::initialize();
    vdbfusion::VDBVolume volume(float(a.voxel), float(a.trunc), a.space_carving);
    std::vector<double> integrate_ms;
    std::size_t points = 0;
    using Clock = std::chrono::steady_clock;
    for (std::size_t i = a.first + a.offset; i < last; i += a.every) {
        std::vector<Eigen::Vector3d> scan = read_scan(files[i]);
        if (a.correct_scan) correct_scan(scan);
        const Eigen::Matrix3d R = poses[i].topLeftCorner<3, 3>();
        const Eigen::Vector3d t = poses[i].topRightCorner<3, 1>();
        std::vector<Eigen::Vector3d> world;
        world.reserve(scan.size());
        for (const Eigen::Vector3d& p : scan) {
            const double r = p.norm();
            if (r >= a.min_range && r <= a.max_range) world.push_back(R * p + t);
        }
        points += world.size();
        const auto t0 = Clock::now();
        volume.Integrate(world, t, [](float /*sdf*/) { return 1.0f; });
        integrate_ms.push_back(ms_between(t0, Clock::now()));
    }

    const auto t0 = Clock::now();
    const auto [vertices, triangles] =
        volume.ExtractTriangleMesh(a.fill_holes, float(a.min_weight));
    const double mesh_ms = ms_between(t0, Clock::now());
    write_mesh(a.out, vertices, triangles);

    double sum = 0.0;
    for (const double x : integrate_ms) sum += x;
    const double scans = double(integrate_ms.size());
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    std::printf("vdbfusion_runner: %s, scans %zu..%zu every %zu from %zu: %zu integrated\n",
                a.dir.c_str(), a.first, last, a.every, a.first + a.offset, integrate_ms.size());
    std::printf(
        "  settings: voxel %.3f m, truncation %.3f m, space carving %d, range %.2f..%.2f m, "
        "min weight %.2f, fill holes %d, correct scan %d\n",
        a.voxel, a.trunc, int(a.space_carving), a.min_range, a.max_range, a.min_weight,
        int(a.fill_holes), int(a.correct_scan));
    std::printf("  points integrated: %zu (%.0f a scan)\n", points, double(points) / scans);
    std::printf("  integration ms a scan: mean %.2f median %.2f p90 %.2f max %.2f (one thread)\n",
                sum / scans, percentile(integrate_ms, 0.5), percentile(integrate_ms, 0.9),
                *std::max_element(integrate_ms.begin(), integrate_ms.end()));
    std::printf("  meshing: %.1f ms (ExtractTriangleMesh)\n", mesh_ms);
    std::printf("  active voxels: %llu\n",
                static_cast<unsigned long long>(volume.tsdf_->activeVoxelCount()));
    std::printf("  mesh: %zu vertices, %zu faces\n", vertices.size(), triangles.size());
    std::printf("  peak memory %.0f MiB\n  wrote %s\n", double(usage.ru_maxrss) / 1024.0,
                a.out.c_str());
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    try {
        Args a;
        if (!parse_args(argc, argv, a)) return 0;
        return run(a);
    } catch (const std::exception& e) {  // UserError, and anything OpenVDB throws
        std::cerr << "vdbfusion_runner: " << e.what() << "\n";
        return 1;
    }
}
