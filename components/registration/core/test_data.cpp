#include "registration/core/test_data.hpp"

#include <filesystem>
#include <random>

#include "common/core/kitti_io.hpp"
#include "registration/core/voxel_grid.hpp"

namespace ltm::registration::test {

std::string shared_kitti00() {
    const std::string dir = LTM_SOURCE_DIR "/../shared/data/kitti/sequences/00";
    return std::filesystem::exists(dir + "/velodyne/000015.bin") ? dir : std::string();
}

std::string fixture_kitti00() { return LTM_SOURCE_DIR "/tests/fixtures/kitti00_mini"; }

KittiSnippet load_kitti(const std::string& dir, std::size_t count) {
    KittiSnippet s;
    const std::vector<std::string> files = common::list_kitti_scans(dir);
    const common::PoseList cam = common::read_kitti_poses(dir + "/poses_semantickitti.txt");
    const common::PoseList lidar =
        common::camera_to_lidar_poses(cam, common::read_kitti_calib_tr(dir + "/calib.txt"));
    for (std::size_t i = 0; i < count && i < files.size() && i < lidar.size(); ++i) {
        s.scans.push_back(common::read_kitti_bin(files[i]));
        s.scans.back().stamp = 0.1 * double(i);
        s.poses.push_back(lidar[i]);
    }
    return s;
}

std::vector<Eigen::Vector3f> every_nth(const std::vector<Eigen::Vector3f>& points,
                                       std::size_t stride, std::size_t first) {
    std::vector<Eigen::Vector3f> out;
    for (std::size_t i = first; i < points.size(); i += stride) out.push_back(points[i]);
    return out;
}

std::vector<Eigen::Vector3f> transformed(const std::vector<Eigen::Vector3f>& points,
                                         const Eigen::Isometry3d& T) {
    const Eigen::Isometry3f Tf = T.cast<float>();
    std::vector<Eigen::Vector3f> out;
    out.reserve(points.size());
    for (const Eigen::Vector3f& p : points) out.push_back(Tf * p);
    return out;
}

Eigen::Isometry3d xy_yaw(double x, double y, double yaw_deg) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() =
        Eigen::AngleAxisd(yaw_deg * M_PI / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    T.translation() = Eigen::Vector3d(x, y, 0.0);
    return T;
}

std::vector<Eigen::Vector3f> synthetic_scene(std::uint32_t seed, double extent) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-float(extent), float(extent));
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::vector<Eigen::Vector3f> pts;
    // Ground: a jittered 0.5 m grid at z = -1.8 (the sensor ~1.8 m up).
    for (float x = -float(extent); x <= float(extent); x += 0.5f) {
        for (float y = -float(extent); y <= float(extent); y += 0.5f) {
            pts.emplace_back(x + 0.2f * unit(rng), y + 0.2f * unit(rng), -1.8f + 0.02f * unit(rng));
        }
    }
    // Buildings: box walls sampled every 0.3 m.
    for (int b = 0; b < 40; ++b) {
        const Eigen::Vector3f c(u(rng), u(rng), -1.8f);
        const Eigen::Vector3f half(2.0f + 6.0f * unit(rng), 2.0f + 6.0f * unit(rng), 0.0f);
        const float height = 2.0f + 12.0f * unit(rng);
        for (float h = 0.0f; h <= height; h += 0.3f) {
            for (float s = -1.0f; s <= 1.0f; s += 0.3f / (2.0f * half.x())) {
                pts.emplace_back(c.x() + s * half.x(), c.y() - half.y(), c.z() + h);
                pts.emplace_back(c.x() + s * half.x(), c.y() + half.y(), c.z() + h);
            }
            for (float s = -1.0f; s <= 1.0f; s += 0.3f / (2.0f * half.y())) {
                pts.emplace_back(c.x() - half.x(), c.y() + s * half.y(), c.z() + h);
                pts.emplace_back(c.x() + half.x(), c.y() + s * half.y(), c.z() + h);
            }
        }
    }
    // Poles.
    for (int p = 0; p < 60; ++p) {
        const float x = u(rng), y = u(rng), height = 3.0f + 5.0f * unit(rng);
        for (float h = 0.0f; h <= height; h += 0.1f) pts.emplace_back(x, y, -1.8f + h);
    }
    return pts;
}

std::vector<Eigen::Vector3f> with_dense_ground(const std::vector<Eigen::Vector3f>& scene) {
    std::vector<Eigen::Vector3f> out = scene;
    for (const Eigen::Vector3f& p : scene) {
        if (p.z() > -1.75f) continue;  // the ground is at z = -1.8 (+2 cm)
        for (const Eigen::Vector3f& d :
             {Eigen::Vector3f(0.25f, 0.0f, 0.0f), Eigen::Vector3f(0.0f, 0.25f, 0.0f),
              Eigen::Vector3f(0.25f, 0.25f, 0.0f)})
            out.push_back(p + d);
    }
    return out;
}

std::vector<Eigen::Vector3f> view(const std::vector<Eigen::Vector3f>& scene,
                                  const Eigen::Isometry3d& T_world_lidar, double range) {
    const Eigen::Isometry3f T = T_world_lidar.inverse().cast<float>();
    const float r2 = float(range * range);
    std::vector<Eigen::Vector3f> out;
    for (const Eigen::Vector3f& p : scene) {
        const Eigen::Vector3f q = T * p;
        if (q.head<2>().squaredNorm() < r2) out.push_back(q);
    }
    return out;
}

common::LocalMapData build_local_map(std::uint64_t id, const Eigen::Isometry3d& T_odom_anchor,
                                     const std::vector<std::vector<Eigen::Vector3f>>& scans,
                                     const common::PoseList& T_odom_lidar, double voxel_size,
                                     double half_extent) {
    // As the odometry builds its local maps: the grid frame is the odometry frame shifted to the
    // anchor position, and only points inside the box around the anchor count.
    registration::VoxelGrid grid(voxel_size, registration::VoxelConfig());
    const Eigen::Vector3d origin = T_odom_anchor.translation();
    const auto in_box = [&](const Eigen::Vector3f& p) {
        return (p.cwiseAbs().array() <= float(half_extent)).all();
    };
    common::LocalMapData d;
    for (std::size_t i = 0; i < scans.size(); ++i) {
        const Eigen::Isometry3d T = T_odom_lidar[i];
        const Eigen::Matrix3f R = T.linear().cast<float>();
        const Eigen::Vector3f t = (T.translation() - origin).cast<float>();
        std::vector<Eigen::Vector3f> pts;
        pts.reserve(scans[i].size());
        for (const Eigen::Vector3f& p : scans[i]) pts.push_back(R * p + t);
        grid.integrate(pts, t, 0.1 * double(i + 1), in_box);
        d.observation_times.push_back(0.1 * double(i + 1));
    }
    d.id = id;
    d.revision = 1;
    d.finished = true;
    d.T_odom_anchor = T_odom_anchor;
    d.T_anchor_grid = T_odom_anchor.inverse() * Eigen::Translation3d(origin);
    d.bbox_min = Eigen::Vector3d::Constant(-half_extent);
    d.bbox_max = Eigen::Vector3d::Constant(half_extent);
    d.voxel_size = float(voxel_size);
    d.voxels = grid.to_data();
    return d;
}

}  // namespace ltm::registration::test
