#include "maintenance/core/observation_map.hpp"

#include <gtest/gtest.h>

#include <random>
#include <set>
#include <tuple>

namespace ltm::maintenance {
namespace {

// Points on the walls and floor of a 30 m x 30 m yard, in region (0, 0).
std::vector<Eigen::Vector3f> yard_points(std::mt19937& rng, int n) {
    std::uniform_real_distribution<float> u(0.5f, 30.0f), h(0.0f, 3.0f);
    std::vector<Eigen::Vector3f> pts;
    for (int i = 0; i < n; ++i) {
        switch (i % 3) {
            case 0:
                pts.emplace_back(u(rng), u(rng), 0.0f);
                break;
            case 1:
                pts.emplace_back(0.5f, u(rng), h(rng));
                break;
            default:
                pts.emplace_back(u(rng), 30.0f, h(rng));
                break;
        }
    }
    return pts;
}

TEST(ObservationMap, EveryPointFindsItsVoxelInUnder100BytesAVoxel) {
    MaintenanceConfig c;
    ObservationMap map(c, {0, 0});
    std::mt19937 rng(2);
    std::set<std::tuple<int, int, int>> cells;
    std::vector<Eigen::Vector3f> all;
    for (int scan = 0; scan < 20; ++scan) {
        const std::vector<Eigen::Vector3f> pts = yard_points(rng, 5000);
        map.add_points(pts, 0.1 * scan);
        for (const Eigen::Vector3f& p : pts) {
            const Eigen::Vector3f q = p / float(c.voxel_size);
            cells.insert({int(std::floor(q.x())), int(std::floor(q.y())), int(std::floor(q.z()))});
            all.push_back(p);
        }
    }
    ASSERT_EQ(map.size(), cells.size());
    for (const Eigen::Vector3f& p : all) {
        const std::uint32_t i = map.find(p);
        ASSERT_NE(i, ObservationMap::kNone);
        EXPECT_LE((map.centre(i) - map.cell_centre(i)).cwiseAbs().maxCoeff(),
                  0.5f * map.voxel_size())
            << "a centre inside its cell";
    }
    // Judged by views: histories fill, the state stays the same size.
    View view;
    view.T_world_sensor.translation() = Eigen::Vector3d(15, 15, 1);
    std::vector<Eigen::Vector3f> in_sensor;
    for (const Eigen::Vector3f& p : yard_points(rng, 20000))
        in_sensor.push_back(p - Eigen::Vector3f(15, 15, 1));
    view.image = RangeImage(c.range_image, in_sensor);
    const std::size_t before = map.memory_bytes();
    std::size_t said = 0;
    for (int k = 0; k < 30; ++k) {
        view.map_time = 0.5 * k;
        const JudgeCounts counts = map.judge(view);
        said += counts.hit + counts.free;
    }
    EXPECT_GT(said, 30 * map.size() / 4) << "the views judged most voxels";
    EXPECT_EQ(map.memory_bytes(), before);
    EXPECT_LE(double(map.memory_bytes()) / double(map.size()), 100.0);
    // Half erased: the rest still found, the erased not.
    std::vector<bool> remove(map.size());
    for (std::size_t i = 0; i < remove.size(); i += 2) remove[i] = true;
    std::vector<registration::VoxelKey> kept, gone;
    for (std::uint32_t i = 0; i < map.size(); ++i) (remove[i] ? gone : kept).push_back(map.key(i));
    map.erase(remove);
    ASSERT_EQ(map.size(), kept.size());
    const auto at = [&](registration::VoxelKey k) {
        return ((registration::unpack_key(k).cast<float>().array() + 0.5f) * map.voxel_size())
            .matrix()
            .eval();
    };
    for (registration::VoxelKey k : kept) EXPECT_NE(map.find(at(k)), ObservationMap::kNone);
    for (registration::VoxelKey k : gone) EXPECT_EQ(map.find(at(k)), ObservationMap::kNone);
    EXPECT_LE(double(map.memory_bytes()) / double(map.size()), 100.0);
}

}  // namespace
}  // namespace ltm::maintenance
