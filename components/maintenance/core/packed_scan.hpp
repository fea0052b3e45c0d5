#pragma once
// A scan's points kept compact while they wait for the maintenance worker (issue 28 item 3: up to
// a pass's worth of scans wait, 300 scans of 44 k points were ~158 MiB): lossless, so the worker
// unpacks exactly the points it would have had and its decisions do not change.
//
// Each coordinate's float bits as a column, each value the difference (mod 2^32) to the previous
// point's (a spinning sensor's neighbours are close), the columns' bytes grouped by byte position
// (all lowest bytes, ..., all highest bytes), then zstd.
#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace ltm::maintenance {

struct PackedScan {
    std::uint32_t count = 0;          // points
    std::vector<std::uint8_t> bytes;  // zstd frame of the shuffled columns

    // What it holds in memory [B] (the points unpacked: 12 B each).
    std::size_t memory_bytes() const { return sizeof(PackedScan) + bytes.capacity(); }
};

// level: zstd's (1..19; 1: a KITTI scan of 127 k points in 9 ms, unpacked in 3.5 ms, 62 % of its
// 12 B a point: the mantissas' low bytes are noise). Throws std::invalid_argument for a
// level out of range.
PackedScan pack_points(const std::vector<Eigen::Vector3f>& points, int level = 1);

// The points back, bit for bit. Throws common::FormatError ("packed scan: ...", one line) when the
// bytes are not a packed scan of `count` points.
std::vector<Eigen::Vector3f> unpack_points(const PackedScan& packed);

}  // namespace ltm::maintenance
