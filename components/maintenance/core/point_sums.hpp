#pragma once
// A maintenance voxel's points in 20 bytes: their count (at most kMaxPoints, enough for a centre
// and a normal) and the sums of q and q q^T in fixed point, q the point relative to the cell's
// centre. q is rounded to 1/256 of the voxel edge (1 mm for 0.25 m voxels), so the sums of 64
// points fit int16 exactly (|q| <= 127 units) and the products, in units of 32 units^2, too.
// registration::VoxelSums is what the centre, the normal and the ground test read.
#include <Eigen/Core>
#include <array>
#include <cstdint>

#include "registration/core/voxel.hpp"

namespace ltm::maintenance {

struct PointSums {
    static constexpr int kMaxPoints = 64;
    // q's unit: the voxel edge / 256; |q| <= 127 units keeps every centre inside its cell.
    static constexpr float kUnitsPerVoxel = 256.0f;
    static constexpr float kSquareUnit = 32.0f;  // sum_sq's unit: 32 q units^2

    std::array<std::int16_t, 3> sum{};     // sum of q [q units]
    std::array<std::int16_t, 6> sum_sq{};  // xx xy xz yy yz zz [kSquareUnit q units^2]
    std::uint8_t count = 0;

    // q relative to the cell centre [m] (clamped to the cell); ignored once kMaxPoints are in.
    void add(const Eigen::Vector3f& q, float voxel_size);
    registration::VoxelSums sums(float voxel_size) const;
};

}  // namespace ltm::maintenance
