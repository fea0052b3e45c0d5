#include "map/core/local_map_columns.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <unordered_map>

#include "common/core/column_block.hpp"

namespace ltm::map {
namespace {

enum Column : std::size_t {
    kIndex,
    kCentre,
    kNormalXY,
    kNormalZ,
    kCount,
    kPlanarity,
    kStability,
    kCreatedRef,
    kCreated,
    kLastRef,
    kLast,
    kObservations,
    kHealth,
    kSeenCount,
    kSeen,
    kColumns
};
const std::vector<std::size_t> kWidths = {4, 4, 4, 4, 4, 4, 4, 4, 8, 4, 8, 4, 4, 2, 2};

std::uint32_t bits(float f) {
    std::uint32_t u;
    std::memcpy(&u, &f, 4);
    return u;
}
float from_bits(std::uint32_t u) {
    float f;
    std::memcpy(&f, &u, 4);
    return f;
}
std::uint64_t bits(double d) {
    std::uint64_t u;
    std::memcpy(&u, &d, 8);
    return u;
}
double double_from(std::uint64_t u) {
    double d;
    std::memcpy(&d, &u, 8);
    return d;
}

// The middle of a cell along one axis (the centre's prediction).
float middle(std::int32_t index, float voxel_size) { return (float(index) + 0.5f) * voxel_size; }
// The normal's z as the unit length predicts it from x and y (0 <= z).
float predicted_z(float x, float y) { return std::sqrt(std::max(0.0f, 1.0f - x * x - y * y)); }

}  // namespace

void write_voxel_columns(common::ByteWriter& w, const common::LocalMapData& map) {
    std::unordered_map<std::uint64_t, std::uint32_t> time_index;  // bits -> 1 + first index
    for (std::size_t i = 0; i < map.observation_times.size(); ++i)
        time_index.emplace(bits(map.observation_times[i]), std::uint32_t(i + 1));
    const auto time = [&](double t, std::size_t ref, std::size_t raw, common::ColumnBlock& b) {
        const auto it = time_index.find(bits(t));
        b.put(ref, it == time_index.end() ? std::uint32_t(0) : it->second);
        if (it == time_index.end()) b.put(raw, bits(t));
    };
    common::ColumnBlock b(kWidths);
    Eigen::Vector3i previous = Eigen::Vector3i::Zero();
    for (const common::VoxelData& v : map.voxels) {
        for (int k = 0; k < 3; ++k) {
            b.put(kIndex, std::int32_t(std::uint32_t(v.index[k]) - std::uint32_t(previous[k])));
            b.put(kCentre, bits(v.centre[k]) - bits(middle(v.index[k], map.voxel_size)));
        }
        previous = v.index;
        b.put(kNormalXY, bits(v.normal.x()));
        b.put(kNormalXY, bits(v.normal.y()));
        b.put(kNormalZ, bits(v.normal.z()) - bits(predicted_z(v.normal.x(), v.normal.y())));
        b.put(kCount, v.point_count);
        b.put(kPlanarity, bits(v.planarity));
        b.put(kStability, bits(v.stability));
        time(v.life.created, kCreatedRef, kCreated, b);
        time(v.life.last_seen, kLastRef, kLast, b);
        b.put(kObservations, v.life.observations);
        b.put(kHealth, bits(v.life.health));
        const auto n_seen =
            static_cast<std::uint16_t>(std::min<std::size_t>(v.life.seen.size(), 65535));
        b.put(kSeenCount, n_seen);
        for (std::uint16_t k = 0; k < n_seen; ++k) b.put(kSeen, v.life.seen[k]);
    }
    const std::vector<std::uint8_t> planes = b.planes();
    w.value(std::uint64_t(planes.size()));
    for (std::uint64_t c : b.counts()) w.value(c);
    const std::vector<std::uint8_t> frame =
        common::zstd_compress(planes.data(), planes.size(), common::kColumnZstdLevel);
    w.raw(frame.data(), frame.size());
}

void read_voxel_columns(common::ByteReader& s, common::LocalMapData& map) {
    const std::uint64_t at = s.offset();
    const auto raw = s.get<std::uint64_t>("voxels");
    std::vector<std::uint64_t> counts(kColumns);
    for (std::uint64_t& c : counts) s.value(c, "voxels");
    const std::uint64_t n = map.voxels.size();
    std::uint64_t total = 0;
    for (std::size_t c = 0; c < kColumns; ++c) total += counts[c] * kWidths[c];
    s.check(counts[kIndex] == 3 * n && counts[kCentre] == 3 * n && counts[kNormalXY] == 2 * n &&
                counts[kNormalZ] == n && counts[kCount] == n && counts[kPlanarity] == n &&
                counts[kStability] == n && counts[kCreatedRef] == n && counts[kCreated] <= n &&
                counts[kLastRef] == n && counts[kLast] <= n && counts[kObservations] == n &&
                counts[kHealth] == n && counts[kSeenCount] == n && counts[kSeen] <= 65535 * n &&
                total == raw,
            "voxels", at, "column counts that do not fit the voxel count");
    std::vector<std::uint8_t> frame(std::size_t(s.remaining()));
    s.raw(frame.data(), frame.size(), "voxels");
    common::ColumnReader r(
        common::zstd_decompress(frame.data(), frame.size(), std::size_t(raw), s.source(), "voxels"),
        kWidths, counts, s.source());
    const std::size_t n_times = map.observation_times.size();
    const float g = map.voxel_size;
    const auto fail = [&](std::size_t i, const char* what, const std::string& problem) {
        throw common::FormatError(s.source(), "voxels[" + std::to_string(i) + "]." + what, at,
                                  problem);
    };
    const auto time = [&](std::size_t i, std::size_t ref, std::size_t raw_column,
                          const char* what) {
        const auto k = r.get<std::uint32_t>(ref, what);
        if (k == 0) {
            const double t = double_from(r.get<std::uint64_t>(raw_column, what));
            if (!std::isfinite(t)) fail(i, what, "not a finite number");
            return t;
        }
        if (k > n_times)
            fail(i, what,
                 "refers to observation time " + std::to_string(k - 1) + " of " +
                     std::to_string(n_times));
        return map.observation_times[k - 1];
    };
    const auto unit = [&](std::size_t i, float v, const char* what) {
        if (!(v >= -1e-3f && v <= 1.001f))
            fail(i, what, "must be in [0, 1] (got " + std::to_string(v) + ")");
        return v;
    };
    Eigen::Vector3i previous = Eigen::Vector3i::Zero();
    for (std::size_t i = 0; i < map.voxels.size(); ++i) {
        common::VoxelData& v = map.voxels[i];
        for (int k = 0; k < 3; ++k) {
            v.index[k] = std::int32_t(std::uint32_t(previous[k]) +
                                      std::uint32_t(r.get<std::int32_t>(kIndex, "index")));
            v.centre[k] =
                from_bits(r.get<std::uint32_t>(kCentre, "centre") + bits(middle(v.index[k], g)));
            if (!std::isfinite(v.centre[k])) fail(i, "centre", "not a finite number");
        }
        previous = v.index;
        const Eigen::Vector3f lo = v.index.cast<float>() * g;
        const float tol = std::max(1e-3f * g, 1e-6f * v.centre.cwiseAbs().maxCoeff());
        if (((v.centre - lo).array() < -tol).any() ||
            ((lo.array() + g - v.centre.array()) < -tol).any())
            fail(i, "centre", "outside the voxel's cell");
        v.normal.x() = from_bits(r.get<std::uint32_t>(kNormalXY, "normal"));
        v.normal.y() = from_bits(r.get<std::uint32_t>(kNormalXY, "normal"));
        v.normal.z() = from_bits(r.get<std::uint32_t>(kNormalZ, "normal") +
                                 bits(predicted_z(v.normal.x(), v.normal.y())));
        const float nn = v.normal.norm();
        if (!std::isfinite(nn) || (nn != 0.0f && std::abs(nn - 1.0f) > 1e-3f))
            fail(i, "normal", "neither zero nor a unit vector");
        v.point_count = r.get<std::uint32_t>(kCount, "point_count");
        v.planarity =
            unit(i, from_bits(r.get<std::uint32_t>(kPlanarity, "planarity")), "planarity");
        v.stability =
            unit(i, from_bits(r.get<std::uint32_t>(kStability, "stability")), "stability");
        v.life.created = time(i, kCreatedRef, kCreated, "life.created");
        v.life.last_seen = time(i, kLastRef, kLast, "life.last_seen");
        if (!(v.life.last_seen >= v.life.created)) fail(i, "life.last_seen", "before life.created");
        v.life.observations = r.get<std::uint32_t>(kObservations, "life.observations");
        v.life.health =
            unit(i, from_bits(r.get<std::uint32_t>(kHealth, "life.health")), "life.health");
        const auto n_seen = r.get<std::uint16_t>(kSeenCount, "life.seen count");
        v.life.seen.resize(n_seen);
        for (std::uint16_t k = 0; k < n_seen; ++k) {
            v.life.seen[k] = r.get<std::uint16_t>(kSeen, "life.seen");
            if (v.life.seen[k] >= n_times)
                fail(i, "life.seen",
                     "index " + std::to_string(v.life.seen[k]) + " beyond the " +
                         std::to_string(n_times) + " observation times");
        }
    }
    r.expect_end("voxels");
}

}  // namespace ltm::map
