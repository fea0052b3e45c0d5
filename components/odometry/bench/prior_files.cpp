#include "odometry/bench/prior_files.hpp"

#include <fstream>
#include <sstream>

#include "common/core/io_error.hpp"

namespace ltm::odometry::bench {
namespace {

// Calls `row(values)` for every line that is not a comment; a line with fewer than `min_values`
// numbers is an error naming the file and line.
template <typename Row>
void read_rows(const std::string& path, std::size_t min_values, Row row) {
    std::ifstream in(path);
    if (!in) throw common::IoError(path, "cannot read");
    std::string line;
    int number = 0;
    while (std::getline(in, line)) {
        ++number;
        if (line.empty() || line[0] == '#') continue;
        std::istringstream s(line);
        std::string first;
        s >> first;
        std::vector<double> v;
        double x = 0.0;
        while (s >> x) v.push_back(x);
        if (v.size() + 1 < min_values || !s.eof()) {
            throw common::IoError(path, "line " + std::to_string(number) + ": expected at least " +
                                            std::to_string(min_values) + " numbers");
        }
        row(first, v);
    }
}

Eigen::Isometry3d pose_of(const std::vector<double>& v, std::size_t at) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = Eigen::Vector3d(v[at], v[at + 1], v[at + 2]);
    T.linear() =
        Eigen::Quaterniond(v[at + 6], v[at + 3], v[at + 4], v[at + 5]).normalized().matrix();
    return T;
}

}  // namespace

PriorSamples read_prior_samples(const std::string& dir, bool imu, bool wheel,
                                MotionPriorConfig* config) {
    PriorSamples out;
    const std::string extrinsics = dir + "/extrinsics.txt";
    bool has_imu = false, has_base = false;
    read_rows(extrinsics, 8, [&](const std::string& name, const std::vector<double>& v) {
        if (name == "T_lidar_imu") {
            config->T_lidar_imu = pose_of(v, 0);
            has_imu = true;
        } else if (name == "T_lidar_base") {
            config->T_lidar_base = pose_of(v, 0);
            has_base = true;
        } else {
            throw common::IoError(extrinsics,
                                  "unknown name '" + name + "' (known: T_lidar_imu, T_lidar_base)");
        }
    });
    if ((imu && !has_imu) || (wheel && !has_base))
        throw common::IoError(extrinsics, imu && !has_imu ? "no T_lidar_imu" : "no T_lidar_base");
    const auto stamp_of = [](const std::string& path, const std::string& first) {
        try {
            std::size_t used = 0;
            const double t = std::stod(first, &used);
            if (used == first.size()) return t;
        } catch (const std::exception&) {
        }
        throw common::IoError(path, "'" + first + "' is not a stamp");
    };
    if (imu) {
        const std::string path = dir + "/imu.txt";
        read_rows(path, 4, [&](const std::string& first, const std::vector<double>& v) {
            out.imu_stamps.push_back(stamp_of(path, first));
            out.gyro.emplace_back(v[0], v[1], v[2]);
        });
    }
    if (wheel) {
        const std::string path = dir + "/wheel_odometry.txt";
        read_rows(path, 8, [&](const std::string& first, const std::vector<double>& v) {
            out.wheel_stamps.push_back(stamp_of(path, first));
            out.wheel_poses.push_back(pose_of(v, 0));
        });
    }
    return out;
}

void feed_prior(const PriorSamples& s, double until, std::size_t* next_imu, std::size_t* next_wheel,
                MotionPrior* prior) {
    for (; *next_imu < s.imu_stamps.size() && s.imu_stamps[*next_imu] <= until; ++*next_imu)
        prior->add_imu(s.imu_stamps[*next_imu], s.gyro[*next_imu]);
    for (; *next_wheel < s.wheel_stamps.size() && s.wheel_stamps[*next_wheel] <= until;
         ++*next_wheel)
        prior->add_wheel(s.wheel_stamps[*next_wheel], s.wheel_poses[*next_wheel]);
}

}  // namespace ltm::odometry::bench
