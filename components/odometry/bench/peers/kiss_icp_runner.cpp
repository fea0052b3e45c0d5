// KISS-ICP (github.com/PRBonn/kiss-icp, MIT licence) run over the scan folders ltm's odometry
// benchmark reads, as a side-by-side peer for ltm_bench_odometry. This file is ltm's own code:
// it only links KISS-ICP's C++ pipeline (kiss_icp::pipeline::KissICP), built from a snapshot of
// its repository by kiss_icp.sh; it is not part of ltm's build.
//
// Settings: KISS-ICP's defaults, a default-constructed KISSConfig (the same values as its Python
// pipeline's defaults, where voxel_size = max_range / 100): voxel_size 1.0 m, max_range 100 m,
// min_range 0 m, max_points_per_voxel 20, initial_threshold 2.0 m, min_motion_th 0.1 m,
// max_num_iterations 500, convergence_criterion 1e-4, max_num_threads 0 (automatic), deskew on.
// The only thing changed is the thread count: a tbb::global_control held for the whole run limits
// TBB to one thread (TBB takes the smallest of all live limits, so KISS-ICP's own global_control
// for "automatic" cannot raise it), for a one-thread comparison with ltm.
//
// De-skewing: KISS-ICP de-skews only with per-point timestamps (the Preprocessor skips it when the
// timestamps vector is empty); the scan stamps of times.txt are never used by its pipeline (its
// motion model is the last frame-to-frame delta, whatever the time between scans). So this runner
// passes a PCD's per-point time field (t, timestamp, timestamps, time or stamps, the names its
// generic data loader looks for) when there is one, and nothing otherwise: KITTI .bin scans and
// the shared Livox PCDs (x y z intensity) are registered without de-skewing, as KISS-ICP's own
// loaders would. times.txt is read only to check it covers the scans, to report the span and to
// place absolute per-point times (see below).
//
// Pose time: when KISS-ICP de-skews, it moves every point to the time of the LAST point of the
// sweep (Preprocessor: pose exp((s - 1) omega) for the normalised time s), so its pose is the
// sensor's at the end of the sweep, while the scan stamp of times.txt and the references (ltm's
// poses, the simulator's poses.txt) are at per-point time 0 (the stamp). With --pose-at stamp
// (the default) the runner reports the pose at the stamp by KISS-ICP's own in-sweep motion model:
// T_world_end * exp((s0 - 1) omega), s0 the stamp's normalised time, omega the log of the motion
// KISS-ICP de-skewed that scan with (its last frame-to-frame delta). Per-point times more than
// 1e4 s from 0 are taken as absolute and the stamp is the scan's line of times.txt. --pose-at end
// writes KISS-ICP's pose as it is. Without per-point times both are the same.
//
// --kitti-correction applies the 0.205 deg vertical-angle correction of the HDL-64E scans that
// KISS-ICP's KITTI data loader applies (from IMLS-SLAM; written here from its description, a
// rotation of each point by 0.205 deg about the axis point x z). Off by default: a generic folder
// of .bin files is read by KISS-ICP without it.
//
// Output: frames, CPU time of this thread a frame, frames a second by CPU time, and with --out the
// poses T_world_lidar in KITTI format (first pose identity), one line a kept scan.
#include <tbb/global_control.h>
#include <time.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sophus/se3.hpp>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "kiss_icp/pipeline/KissICP.hpp"

namespace fs = std::filesystem;

namespace {

struct Args {
    std::string dir;
    std::string out;
    std::size_t every = 1;
    std::size_t max_frames = 0;  // 0: all kept scans
    bool kitti_correction = false;
    bool pose_at_stamp = true;  // false: at the end of the sweep, as KISS-ICP reports it
};

// One line for the user; main prints it and exits 1.
struct UserError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

const char* const kUsage =
    "usage: kiss_icp_runner DIR [--every N] [--max-frames N] [--out POSES.txt] "
    "[--kitti-correction] [--pose-at stamp|end]\n"
    "  DIR: KITTI layout (DIR/velodyne/*.bin or DIR/*.bin, times.txt beside velodyne/) or a PCD\n"
    "       folder (DIR/Scans/*.pcd or DIR/*.pcd, binary or ascii, times.txt in DIR)\n"
    "  --every N        keep every Nth scan (0, N, 2N, ...)\n"
    "  --max-frames N   stop after N kept scans (0: all)\n"
    "  --out FILE       write T_world_lidar of each kept scan (KITTI format, first identity)\n"
    "  --kitti-correction  KISS-ICP's KITTI loader's 0.205 deg vertical-angle correction\n"
    "  --pose-at stamp|end  de-skewed scans: the pose at the scan stamp (default) or at the end\n"
    "                   of the sweep, where KISS-ICP puts it\n"
    "Runs KISS-ICP's pipeline with its default KISSConfig on one TBB thread.\n";

std::size_t parse_count(const std::string& option, const char* text, bool allow_zero) {
    char* end = nullptr;
    errno = 0;
    const long long v = std::strtoll(text, &end, 10);
    if (end == text || *end != '\0' || errno != 0 || v < 0 || (v == 0 && !allow_zero))
        throw UserError(option + ": expected a " + (allow_zero ? "non-negative" : "positive") +
                        " integer, got '" + text + "'");
    return std::size_t(v);
}

// Returns false after printing the usage (--help).
bool parse_args(int argc, char** argv, Args& a) {
    for (int i = 1; i < argc; ++i) {
        const std::string s = argv[i];
        const auto value = [&]() -> const char* {
            if (i + 1 >= argc) throw UserError(s + ": needs a value");
            return argv[++i];
        };
        if (s == "-h" || s == "--help") {
            std::cout << kUsage;
            return false;
        } else if (s == "--every") {
            a.every = parse_count(s, value(), false);
        } else if (s == "--max-frames") {
            a.max_frames = parse_count(s, value(), true);
        } else if (s == "--out") {
            a.out = value();
        } else if (s == "--kitti-correction") {
            a.kitti_correction = true;
        } else if (s == "--pose-at") {
            const std::string v = value();
            if (v != "stamp" && v != "end")
                throw UserError("--pose-at: stamp or end, got '" + v + "'");
            a.pose_at_stamp = v == "stamp";
        } else if (!s.empty() && s[0] == '-') {
            throw UserError("unknown option '" + s + "' (--help)");
        } else if (a.dir.empty()) {
            a.dir = s;
        } else {
            throw UserError("one folder only, got '" + a.dir + "' and '" + s + "'");
        }
    }
    if (a.dir.empty()) throw UserError("no scan folder given (--help)");
    return true;
}

std::vector<std::string> files_with_extension(const fs::path& dir, const std::string& ext) {
    std::vector<std::string> files;
    if (!fs::is_directory(dir)) return files;
    for (const auto& e : fs::directory_iterator(dir))
        if (e.is_regular_file() && e.path().extension() == ext) files.push_back(e.path().string());
    std::sort(files.begin(), files.end());
    return files;
}

struct Folder {
    std::vector<std::string> scans;
    bool kitti = false;
    fs::path times_file;  // empty: none
};

// The same layouts as ltm's ScanFolder: KITTI .bin first, then PCD files.
Folder find_scans(const std::string& path) {
    const fs::path dir(path);
    if (!fs::is_directory(dir)) throw UserError(path + ": not a folder");
    Folder f;
    if (!(f.scans = files_with_extension(dir / "velodyne", ".bin")).empty()) {
        f.kitti = true;
        f.times_file = dir / "times.txt";
    } else if (!(f.scans = files_with_extension(dir, ".bin")).empty()) {
        f.kitti = true;
        f.times_file =
            dir.filename() == "velodyne" ? dir.parent_path() / "times.txt" : dir / "times.txt";
    } else {
        const fs::path cloud_dir = fs::is_directory(dir / "Scans") ? dir / "Scans" : dir;
        f.scans = files_with_extension(cloud_dir, ".pcd");
        f.times_file = dir / "times.txt";
        if (f.scans.empty())
            throw UserError(path +
                            ": no scans (expected velodyne/*.bin, *.bin, Scans/*.pcd or "
                            "*.pcd)");
    }
    if (!fs::is_regular_file(f.times_file)) f.times_file.clear();
    return f;
}

std::vector<double> read_times(const fs::path& file) {
    std::ifstream in(file);
    if (!in) throw UserError(file.string() + ": cannot read");
    std::vector<double> times;
    std::string line;
    while (std::getline(in, line)) {
        if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
        std::istringstream ls(line);
        double t = 0.0;
        if (!(ls >> t))
            throw UserError(file.string() + ": line " + std::to_string(times.size() + 1) +
                            " is not a time");
        times.push_back(t);
    }
    return times;
}

struct Scan {
    std::vector<Eigen::Vector3d> points;
    std::vector<double> timestamps;  // per point; empty when the scan has none
};

Scan read_kitti_bin(const std::string& file) {
    std::ifstream in(file, std::ios::binary | std::ios::ate);
    if (!in) throw UserError(file + ": cannot read");
    const std::streamoff bytes = in.tellg();
    if (bytes % 16 != 0)
        throw UserError(file + ": " + std::to_string(bytes) +
                        " bytes is not a whole number of 16-byte x y z intensity points");
    std::vector<float> data(std::size_t(bytes) / 4);
    in.seekg(0);
    in.read(reinterpret_cast<char*>(data.data()), bytes);
    if (!in) throw UserError(file + ": short read");
    Scan scan;
    scan.points.reserve(data.size() / 4);
    for (std::size_t i = 0; i + 3 < data.size(); i += 4) {
        const Eigen::Vector3d p(data[i], data[i + 1], data[i + 2]);
        if (p.allFinite()) scan.points.push_back(p);
    }
    return scan;
}

struct PcdField {
    std::string name;
    std::size_t size = 4;
    char type = 'F';
    std::size_t count = 1;
    std::size_t offset = 0;  // bytes into a binary point
};

double field_value(const PcdField& f, const char* p) {
    if (f.type == 'F' && f.size == 4) {
        float v;
        std::memcpy(&v, p, 4);
        return v;
    }
    if (f.type == 'F' && f.size == 8) {
        double v;
        std::memcpy(&v, p, 8);
        return v;
    }
    if (f.type == 'U' || f.type == 'I') {
        std::uint64_t u = 0;
        std::memcpy(&u, p, f.size);  // little-endian host, as PCD files are written
        if (f.type == 'I' && f.size < 8 && (u >> (8 * f.size - 1)) & 1u)
            return double(std::int64_t(u | (~std::uint64_t(0) << (8 * f.size))));
        return f.type == 'I' ? double(std::int64_t(u)) : double(u);
    }
    return 0.0;
}

// PCD v0.7, DATA binary or ascii; x y z of any numeric type, plus a per-point time field if any.
Scan read_pcd(const std::string& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in) throw UserError(file + ": cannot read");
    std::vector<PcdField> fields;
    std::size_t points = 0;
    std::string data, line;
    std::vector<std::size_t> sizes, counts;
    std::vector<char> types;
    while (data.empty() && std::getline(in, line)) {
        if (!line.empty() && line.back() == '\r') line.pop_back();
        std::istringstream ls(line);
        std::string key;
        ls >> key;
        if (key.empty() || key[0] == '#') continue;
        std::string w;
        if (key == "FIELDS") {
            while (ls >> w) fields.push_back({w, 4, 'F', 1, 0});
        } else if (key == "SIZE") {
            while (ls >> w) sizes.push_back(std::size_t(std::atoi(w.c_str())));
        } else if (key == "TYPE") {
            while (ls >> w) types.push_back(w.empty() ? '?' : w[0]);
        } else if (key == "COUNT") {
            while (ls >> w) counts.push_back(std::size_t(std::atoi(w.c_str())));
        } else if (key == "POINTS") {
            ls >> points;
        } else if (key == "DATA") {
            ls >> data;
        }
    }
    if (data != "binary" && data != "ascii")
        throw UserError(file + ": PCD DATA '" + data + "' (binary or ascii only)");
    if (sizes.size() != fields.size() || types.size() != fields.size())
        throw UserError(file + ": PCD FIELDS, SIZE and TYPE disagree");
    std::size_t stride = 0;
    int ix = -1, iy = -1, iz = -1, it = -1;
    for (std::size_t k = 0; k < fields.size(); ++k) {
        PcdField& f = fields[k];
        f.size = sizes[k];
        f.type = types[k];
        f.count = k < counts.size() ? counts[k] : 1;
        if (f.size != 1 && f.size != 2 && f.size != 4 && f.size != 8)
            throw UserError(file + ": PCD field '" + f.name + "' has size " +
                            std::to_string(f.size));
        f.offset = stride;
        stride += f.size * f.count;
        const int idx = int(k);
        if (f.name == "x") ix = idx;
        if (f.name == "y") iy = idx;
        if (f.name == "z") iz = idx;
        for (const char* t : {"t", "timestamp", "timestamps", "time", "stamps"})
            if (it < 0 && f.name == t) it = idx;
    }
    if (ix < 0 || iy < 0 || iz < 0) throw UserError(file + ": PCD without x y z fields");
    Scan scan;
    scan.points.reserve(points);
    const auto add = [&](const Eigen::Vector3d& p, double t) {
        if (!p.allFinite()) return;
        scan.points.push_back(p);
        if (it >= 0) scan.timestamps.push_back(t);
    };
    if (data == "binary") {
        std::vector<char> buf(points * stride);
        in.read(buf.data(), std::streamsize(buf.size()));
        if (std::size_t(in.gcount()) != buf.size())
            throw UserError(file + ": PCD ends before its " + std::to_string(points) + " points");
        for (std::size_t i = 0; i < points; ++i) {
            const char* p = buf.data() + i * stride;
            add({field_value(fields[ix], p + fields[ix].offset),
                 field_value(fields[iy], p + fields[iy].offset),
                 field_value(fields[iz], p + fields[iz].offset)},
                it >= 0 ? field_value(fields[it], p + fields[it].offset) : 0.0);
        }
    } else {
        // ascii: one value a field element, in order.
        std::vector<std::size_t> first(fields.size());
        std::size_t values = 0;
        for (std::size_t k = 0; k < fields.size(); ++k) {
            first[k] = values;
            values += fields[k].count;
        }
        std::vector<double> v(values);
        for (std::size_t i = 0; i < points; ++i) {
            for (double& x : v)
                if (!(in >> x))
                    throw UserError(file + ": PCD ascii data ends at point " + std::to_string(i));
            add({v[first[ix]], v[first[iy]], v[first[iz]]}, it >= 0 ? v[first[it]] : 0.0);
        }
    }
    return scan;
}

// The vertical-angle correction of KITTI's HDL-64E scans (IMLS-SLAM): each point turned by
// 0.205 deg about the horizontal axis perpendicular to it.
void correct_kitti_scan(std::vector<Eigen::Vector3d>& points) {
    const double angle = 0.205 * M_PI / 180.0;
    for (Eigen::Vector3d& p : points) {
        const Eigen::Vector3d axis = p.cross(Eigen::Vector3d::UnitZ());
        if (axis.norm() < 1e-12) continue;
        p = Eigen::AngleAxisd(angle, axis.normalized()) * p;
    }
}

double thread_cpu_seconds() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

void write_pose(std::ofstream& out, const Eigen::Matrix4d& T) {
    char line[512];
    std::snprintf(line, sizeof(line),
                  "%.9g %.9g %.9g %.9g %.9g %.9g %.9g %.9g %.9g %.9g %.9g %.9g\n", T(0, 0), T(0, 1),
                  T(0, 2), T(0, 3), T(1, 0), T(1, 1), T(1, 2), T(1, 3), T(2, 0), T(2, 1), T(2, 2),
                  T(2, 3));
    out << line;
}

int run(const Args& a) {
    // One TBB thread for the whole run (see the top of this file).
    const tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);

    const Folder folder = find_scans(a.dir);
    std::vector<double> times;
    if (!folder.times_file.empty()) {
        times = read_times(folder.times_file);
        if (times.size() < folder.scans.size())
            throw UserError(folder.times_file.string() + ": " + std::to_string(times.size()) +
                            " times for " + std::to_string(folder.scans.size()) + " scans");
    }
    std::vector<std::size_t> kept;
    for (std::size_t i = 0; i < folder.scans.size(); i += a.every) {
        if (a.max_frames && kept.size() == a.max_frames) break;
        kept.push_back(i);
    }

    std::ofstream out;
    if (!a.out.empty()) {
        out.open(a.out);
        if (!out) throw UserError(a.out + ": cannot write");
    }

    const kiss_icp::pipeline::KISSConfig config;  // KISS-ICP's defaults
    kiss_icp::pipeline::KissICP kiss(config);
    std::printf(
        "%s: %zu of %zu %s scans (every %zu)%s; KISS-ICP defaults: voxel %.2f m, "
        "max range %.0f m, deskew %s, 1 TBB thread; poses at the %s\n",
        a.dir.c_str(), kept.size(), folder.scans.size(), folder.kitti ? "kitti" : "pcd", a.every,
        folder.times_file.empty() ? " (no times.txt)" : "", config.voxel_size, config.max_range,
        config.deskew ? "on (per-point times only)" : "off",
        a.pose_at_stamp ? "scan stamp" : "end of the sweep");

    double cpu = 0.0, io = 0.0;
    std::size_t deskewed = 0, points = 0;
    std::vector<double> ms;
    for (const std::size_t i : kept) {
        const double c0 = thread_cpu_seconds();
        Scan scan = folder.kitti ? read_kitti_bin(folder.scans[i]) : read_pcd(folder.scans[i]);
        const double c1 = thread_cpu_seconds();
        if (scan.points.empty()) std::fprintf(stderr, "scan %zu: no points\n", i);
        if (a.kitti_correction) correct_kitti_scan(scan.points);
        const Sophus::SE3d deskew_motion = kiss.delta();  // what this scan is de-skewed with
        kiss.RegisterFrame(scan.points, scan.timestamps);
        const double c2 = thread_cpu_seconds();
        io += c1 - c0;
        cpu += c2 - c1;
        ms.push_back(1000.0 * (c2 - c1));
        deskewed += !scan.timestamps.empty();
        points += scan.points.size();
        Sophus::SE3d pose = kiss.pose();  // T_world_lidar; the first is identity
        if (a.pose_at_stamp && config.deskew && !scan.timestamps.empty()) {
            const auto [lo, hi] =
                std::minmax_element(scan.timestamps.begin(), scan.timestamps.end());
            const bool absolute = std::abs(*lo) > 1e4 && !times.empty();
            const double stamp = absolute ? times[i] : 0.0;
            if (*hi > *lo) {
                const double s0 = (stamp - *lo) / (*hi - *lo);
                pose = pose * Sophus::SE3d::exp((s0 - 1.0) * deskew_motion.log());
            }
        }
        if (out) write_pose(out, pose.matrix());
    }
    const std::size_t n = kept.size();
    std::sort(ms.begin(), ms.end());
    std::printf("frames: %zu; points a frame %.0f; de-skewed (per-point times) %zu\n", n,
                n ? double(points) / n : 0.0, deskewed);
    if (n) {
        std::printf("speed by CPU time of the odometry thread: %.1f frames/s (%.2f ms a frame)\n",
                    n / cpu, 1000.0 * cpu / n);
        std::printf("time a frame (CPU): median %.2f ms  p95 %.2f  max %.2f; reading %.2f ms\n",
                    ms[ms.size() / 2], ms[std::min(ms.size() - 1, std::size_t(0.95 * ms.size()))],
                    ms.back(), 1000.0 * io / n);
    }
    if (!times.empty() && n > 1)
        std::printf("sensor time covered: %.2f s\n", times[kept.back()] - times[kept.front()]);
    if (out) {
        out.close();
        if (!out) throw UserError(a.out + ": write failed");
        std::printf("poses: %s (T_world_lidar, KITTI format)\n", a.out.c_str());
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    try {
        Args args;
        if (!parse_args(argc, argv, args)) return 0;
        return run(args);
    } catch (const UserError& e) {
        std::fprintf(stderr, "kiss_icp_runner: %s\n", e.what());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "kiss_icp_runner: %s\n", e.what());
    }
    return 1;
}
