#include "maintenance/core/observation_map.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>

namespace ltm::maintenance {

static_assert(sizeof(ObservedVoxel) <= 84, "the per-voxel state grew: see README's figures");
static_assert(VoxelHistory::kCapacity == 6, "maintenance_config.hpp: max_slots is in [2, 6]");

std::uint32_t to_ticks(double map_time) {
    const double t = std::floor(map_time * kTicksPerSecond);
    if (!(t > 0.0)) return 0;
    return t >= 4294967295.0 ? 0xffffffffu : std::uint32_t(t);
}

ObservationMap::ObservationMap(const MaintenanceConfig& config, const Eigen::Vector2i& region)
    : config_(config),
      region_(region),
      voxel_size_(float(config.voxel_size)),
      inv_voxel_size_(1.0f / float(config.voxel_size)) {}

void ObservationMap::append(const ObservedVoxel& voxel) {
    if (voxels_.size() == voxels_.capacity())
        voxels_.reserve(voxels_.size() + voxels_.size() / 16 + 64);
    voxels_.push_back(voxel);
}

void ObservationMap::reserve(std::size_t n) {
    if (n > voxels_.capacity()) voxels_.reserve(n);
}

std::uint32_t ObservationMap::insert(registration::VoxelKey key, double map_time) {
    const auto key_of = [this](std::uint32_t i) { return voxels_[i].key(); };
    const std::uint32_t found = index_.find(key, key_of);
    if (found != kNone) return found;
    ObservedVoxel v;
    v.set_key(key);
    v.created_ticks = v.last_point_ticks = to_ticks(map_time);
    const auto i = std::uint32_t(voxels_.size());
    append(v);
    index_.insert(key, i, key_of);
    return i;
}

void ObservationMap::add_points(const std::vector<Eigen::Vector3f>& points, double map_time,
                                double established_before) {
    const std::uint32_t ticks = to_ticks(map_time);
    const auto key_of = [this](std::uint32_t j) { return voxels_[j].key(); };
    // A cell next to a voxel created before `established_before` (ticks) is a surface already
    // there: a point there adds nothing new (established_before < 0: every cell may be created).
    const bool guarded = established_before >= 0.0;
    const std::uint32_t before = guarded ? to_ticks(established_before) : 0;
    const auto beside_established = [&](const Eigen::Vector3i& c) {
        for (int d = 0; d < 27; ++d) {
            if (d == 13) continue;  // the cell itself
            const Eigen::Vector3i n = c + Eigen::Vector3i(d % 3 - 1, d / 3 % 3 - 1, d / 9 - 1);
            const std::uint32_t j =
                index_.find(registration::pack_key(n.x(), n.y(), n.z()), key_of);
            if (j != kNone && voxels_[j].created_ticks < before) return true;
        }
        return false;
    };
    // A scan's points come many to a cell: the answers of recent cells are kept (a small
    // direct-mapped table), and a point in a cell whose voxel is full (PointSums::kMaxPoints)
    // and already stamped by this call touches nothing. Within this call a cell's answer cannot
    // change: a voxel keeps its index, and a cell left out beside an established voxel stays
    // out (voxels made now are not established).
    struct Recent {
        registration::VoxelKey key = ~registration::VoxelKey(0);  // never a packed key
        std::uint32_t index = kNone;
        bool done = false;  // full and stamped: nothing left for this call to do
    };
    constexpr std::size_t kRecent = 256;
    std::array<Recent, kRecent> recent{};
    for (const Eigen::Vector3f& p : points) {
        Eigen::Vector3i c;
        if (!p.allFinite() || !registration::voxel_coords(p, inv_voxel_size_, &c)) continue;
        const registration::VoxelKey key = registration::pack_key(c.x(), c.y(), c.z());
        Recent& r = recent[std::size_t((key * 0x9E3779B97F4A7C15ull) >> 56)];
        if (r.key != key) {
            r.key = key;
            r.index = index_.find(key, key_of);
            if (r.index == kNone && !(guarded && beside_established(c)))
                r.index = insert(key, map_time);
            r.done = false;
        }
        if (r.index == kNone || r.done) continue;  // beside an established voxel, or full
        ObservedVoxel& v = voxels_[r.index];
        const Eigen::Vector3f q =
            p - (c.cast<float>() + Eigen::Vector3f::Constant(0.5f)) * voxel_size_;
        v.points.add(q, voxel_size_);  // up to PointSums::kMaxPoints: a centre and a normal
        v.last_point_ticks = std::max(v.last_point_ticks, ticks);
        r.done = v.points.count >= PointSums::kMaxPoints;
    }
}

JudgeCounts ObservationMap::judge(const View& view) {
    JudgeCounts counts;
    const Eigen::Isometry3f T_sensor_world = view.T_world_sensor.inverse().cast<float>();
    const Eigen::Isometry3f T_world_sensor = view.T_world_sensor.cast<float>();
    const Eigen::Vector3f sensor = view.T_world_sensor.translation().cast<float>();
    const float max_range_sq = float(config_.max_range * config_.max_range);
    const auto slot = std::int32_t(std::floor(view.map_time / config_.slot));
    const float half_diagonal = 0.87f * voxel_size_;
    const int max_entries = config_.max_slots;  // validated: at most VoxelHistory::kCapacity
    for (std::size_t i = 0; i < voxels_.size(); ++i) {
        const Eigen::Vector3f c = cell_centre(std::uint32_t(i));
        if ((c - sensor).squaredNorm() > max_range_sq) continue;
        ++counts.voxels;
        const Eigen::Vector3f p = T_sensor_world * c;
        const float range = p.norm();
        const float margin =
            float(config_.free_margin) + half_diagonal + float(config_.free_margin_per_m) * range;
        const float hit_margin =
            float(config_.hit_margin) + half_diagonal + float(config_.hit_margin_per_m) * range;
        ObservedVoxel& v = voxels_[i];
        Eigen::Vector3f behind(0.0f, 0.0f, 0.0f);
        Visibility seen = view.image.classify(p, voxel_size_, margin, hit_margin, &behind);
        // A return just behind the cube on the voxel's own plane is its surface seen at a grazing
        // angle (a hit, as it always was); on another surface (a van's side 0.7 m behind the
        // one that left) it says nothing. A voxel with no plane keeps the old rule (a hit).
        if (seen == Visibility::kUnseen && behind.squaredNorm() > 0.0f) {
            const Eigen::Vector3f n = normal(std::uint32_t(i));
            const float off =
                n.squaredNorm() > 0.0f
                    ? std::abs(n.dot(T_world_sensor * behind - centre(std::uint32_t(i))))
                    : 0.0f;
            const float tolerance = float(config_.hit_margin) + 0.5f * voxel_size_ +
                                    view.image.pixel_half_diagonal() * behind.norm();
            if (off <= tolerance) seen = Visibility::kSurface;
        }
        switch (seen) {
            case Visibility::kSurface:
                v.history.add(slot, true, max_entries);
                ++counts.hit;
                break;
            case Visibility::kFree:
                v.history.add(slot, false, max_entries);
                ++counts.free;
                break;
            case Visibility::kOccluded:
                ++counts.occluded;
                break;
            case Visibility::kUnseen:
                ++counts.unseen;
                break;
        }
    }
    return counts;
}

std::uint32_t ObservationMap::find(const Eigen::Vector3f& p) const {
    Eigen::Vector3i c;
    if (!p.allFinite() || !registration::voxel_coords(p, inv_voxel_size_, &c)) return kNone;
    return index_.find(registration::pack_key(c.x(), c.y(), c.z()),
                       [this](std::uint32_t i) { return voxels_[i].key(); });
}

Eigen::Vector3f ObservationMap::cell_centre(std::uint32_t i) const {
    return (registration::unpack_key(voxels_[i].key()).cast<float>() +
            Eigen::Vector3f::Constant(0.5f)) *
           voxel_size_;
}

Eigen::Vector3f ObservationMap::centre(std::uint32_t i) const {
    const registration::VoxelSums s = voxels_[i].sums(voxel_size_);
    return cell_centre(i) + (s.weight > 0.0f ? s.mean() : Eigen::Vector3f::Zero());
}

Eigen::Vector3f ObservationMap::normal(std::uint32_t i) const {
    const registration::VoxelSums s = voxels_[i].sums(voxel_size_);
    if (s.weight < 3.0f) return Eigen::Vector3f::Zero();
    const Eigen::Matrix3d cov = s.covariance();
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(cov);
    const Eigen::Vector3d l = es.eigenvalues();
    // No plane: no spread in a second direction beyond the sums' rounding (one product unit; a
    // line of points, one ring grazing the voxel, has none), or not 4x the smallest.
    const double unit = double(voxel_size_) / PointSums::kUnitsPerVoxel;
    const double rounding = PointSums::kSquareUnit * unit * unit;
    if (!(l(1) > 4.0 * std::max(l(0), 0.0)) || !(l(1) > rounding)) return Eigen::Vector3f::Zero();
    return es.eigenvectors().col(0).cast<float>().normalized();
}

bool ObservationMap::restore(const ObservedVoxel& voxel) {
    const auto key_of = [this](std::uint32_t i) { return voxels_[i].key(); };
    if (index_.find(voxel.key(), key_of) != kNone) return false;
    const auto i = std::uint32_t(voxels_.size());
    append(voxel);
    index_.insert(voxel.key(), i, key_of);
    return true;
}

void ObservationMap::erase(const std::vector<bool>& remove) {
    std::size_t out = 0;
    for (std::size_t i = 0; i < voxels_.size(); ++i) {
        if (i < remove.size() && remove[i]) continue;
        if (out != i) voxels_[out] = voxels_[i];
        ++out;
    }
    voxels_.resize(out);
    if (voxels_.capacity() > out + out / 16 + 64) voxels_.shrink_to_fit();
    index_.rebuild(out, [this](std::uint32_t i) { return voxels_[i].key(); });
}

std::size_t ObservationMap::memory_bytes() const {
    return index_.memory_bytes() + voxels_.capacity() * sizeof(ObservedVoxel);
}

}  // namespace ltm::maintenance
