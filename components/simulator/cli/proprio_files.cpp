#include "simulator/cli/proprio_files.hpp"

#include <cstdio>

#include "common/core/io_error.hpp"

namespace ltm::sim::cli {
namespace {

struct File {
    File(const std::string& path) : path_(path), f_(std::fopen(path.c_str(), "w")) {
        if (f_ == nullptr) throw common::IoError(path, "cannot write");
    }
    ~File() {
        if (f_ != nullptr) std::fclose(f_);
    }
    void close() {
        const bool ok = std::ferror(f_) == 0;
        if (std::fclose(f_) != 0 || !ok) {
            f_ = nullptr;
            throw common::IoError(path_, "write failed");
        }
        f_ = nullptr;
    }
    std::FILE* get() { return f_; }

  private:
    std::string path_;
    std::FILE* f_;
};

void pose_line(std::FILE* f, const Eigen::Isometry3d& T) {
    const Eigen::Quaterniond q(T.linear());
    std::fprintf(f, " %.6f %.6f %.6f %.9f %.9f %.9f %.9f", T.translation().x(), T.translation().y(),
                 T.translation().z(), q.x(), q.y(), q.z(), q.w());
}

}  // namespace

void write_imu(const std::string& path, const std::vector<ImuSample>& samples, const ImuConfig& c,
               const ImuSimulator& imu) {
    File f(path);
    std::fprintf(f.get(),
                 "# stamp gx gy gz ax ay az  (IMU frame: s, rad/s, m/s^2; T_lidar_imu in "
                 "extrinsics.txt)\n# %.0f Hz; gyro noise %g rad/s/sqrt(Hz), turn-on bias sigma %g "
                 "rad/s, bias walk %g rad/s^2/sqrt(Hz); accel noise %g m/s^2/sqrt(Hz), bias sigma "
                 "%g m/s^2\n# gyro bias at the end %.6f %.6f %.6f rad/s; accel bias %.4f %.4f "
                 "%.4f m/s^2\n",
                 c.rate, c.gyro_noise, c.gyro_bias, c.gyro_bias_walk, c.accel_noise, c.accel_bias,
                 imu.gyro_bias().x(), imu.gyro_bias().y(), imu.gyro_bias().z(),
                 imu.accel_bias().x(), imu.accel_bias().y(), imu.accel_bias().z());
    for (const ImuSample& s : samples) {
        std::fprintf(f.get(), "%.6f %.7f %.7f %.7f %.5f %.5f %.5f\n", s.stamp, s.gyro.x(),
                     s.gyro.y(), s.gyro.z(), s.accel.x(), s.accel.y(), s.accel.z());
    }
    f.close();
}

void write_wheel_odometry(const std::string& path, const std::vector<WheelSample>& samples,
                          const WheelConfig& c, const WheelSimulator& wheel) {
    File f(path);
    std::fprintf(f.get(),
                 "# stamp x y z qx qy qz qw vx vy vz wx wy wz  (base frame in the wheel odometry "
                 "frame; twist in the base frame; T_lidar_base in extrinsics.txt)\n# %.0f Hz; "
                 "distance factor %.4f (sigma %g), turn factor %.4f (sigma %g), slip %g, speed "
                 "noise %g m/s/sqrt(Hz), turn noise %g rad/s/sqrt(Hz)\n",
                 c.rate, wheel.scale(), c.scale_error, wheel.turn_scale(), c.turn_error, c.slip,
                 c.speed_noise, c.turn_noise);
    for (const WheelSample& s : samples) {
        std::fprintf(f.get(), "%.6f", s.stamp);
        pose_line(f.get(), s.T_odom_base);
        std::fprintf(f.get(), " %.5f %.5f %.5f %.6f %.6f %.6f\n", s.linear.x(), s.linear.y(),
                     s.linear.z(), s.angular.x(), s.angular.y(), s.angular.z());
    }
    f.close();
}

void write_extrinsics(const std::string& path, const ImuConfig& imu, const WheelConfig& wheel) {
    File f(path);
    std::fprintf(f.get(), "# NAME x y z qx qy qz qw  (the sensor's frame in the LiDAR frame)\n");
    std::fprintf(f.get(), "T_lidar_imu");
    pose_line(f.get(), imu.T_lidar_imu);
    std::fprintf(f.get(), "\nT_lidar_base");
    pose_line(f.get(), wheel.T_lidar_base);
    std::fprintf(f.get(), "\n");
    f.close();
}

}  // namespace ltm::sim::cli
