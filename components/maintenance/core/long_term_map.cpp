#include "maintenance/core/long_term_map.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "common/core/config_check.hpp"
#include "maintenance/core/derived_thresholds.hpp"

namespace ltm::maintenance {

std::optional<common::ConfigProblem> validate(const MaintenanceConfig& config) {
    common::ConfigChecker k;
    MaintenanceConfig c = config;
    visit_fields(c, "", GivenFields<common::ConfigChecker>{k});
    k.require(c.range_image.min_range < c.range_image.max_range, "range_image.min_range",
              "must be below range_image.max_range");
    k.require(c.change.gone_hit_fraction < c.change.new_hit_fraction, "change.gone_hit_fraction",
              "must be below change.new_hit_fraction");
    return k.problem();
}

LongTermMap::LongTermMap(const MaintenanceConfig& config) : config_(config) {
    common::throw_if(validate(config), "maintenance");
}

void LongTermMap::begin_session(std::uint32_t session, double first_stamp) {
    flush_views();
    // On a tick of the voxels' clock: a voxel of this session is never "created before" it.
    if (in_session_ || now_ > 0.0)
        session_offset_ =
            std::ceil((now_ + config_.session_gap) * kTicksPerSecond) / kTicksPerSecond;
    session_ = session;
    if (sessions_.empty() || sessions_.back() != session) sessions_.push_back(session);
    in_session_ = true;
    session_start_stamp_ = std::isfinite(first_stamp) ? first_stamp : 0.0;
    now_ = session_offset_;
    last_view_time_ = -1e300;
    session_views_ = 0;
}

double LongTermMap::map_time_of(double stamp) const {
    if (!std::isfinite(stamp)) return now_;
    return session_offset_ + std::max(0.0, stamp - session_start_stamp_);
}

Eigen::Vector2i LongTermMap::region_of(const Eigen::Vector3f& p) const {
    const float inv = 1.0f / float(config_.region_size);
    return {int(std::floor(p.x() * inv)), int(std::floor(p.y() * inv))};
}

ObservationMap& LongTermMap::region(const Eigen::Vector2i& key) {
    auto& slot = regions_[{key.x(), key.y()}];
    if (!slot) slot = std::make_unique<ObservationMap>(config_, key);
    return *slot;
}

void LongTermMap::add_scan(const std::vector<Eigen::Vector3f>& points,
                           const Eigen::Isometry3d& T_world_sensor, double stamp) {
    if (!in_session_) begin_session(session_, stamp);
    if (!T_world_sensor.matrix().allFinite()) return;
    const double t = map_time_of(stamp);
    now_ = std::max(now_, t);
    // Points to their regions.
    const Eigen::Isometry3f T = T_world_sensor.cast<float>();
    const float max_range_sq = float(config_.max_range * config_.max_range);
    const float min_range_sq = float(config_.range_image.min_range * config_.range_image.min_range);
    std::map<std::pair<int, int>, std::vector<Eigen::Vector3f>> by_region;
    for (const Eigen::Vector3f& p : points) {
        if (!p.allFinite()) continue;
        const float r2 = p.squaredNorm();
        if (r2 > max_range_sq || r2 < min_range_sq) continue;
        const Eigen::Vector3f q = T * p;
        const Eigen::Vector2i r = region_of(q);
        by_region[{r.x(), r.y()}].push_back(q);
    }
    for (auto& [key, pts] : by_region) region({key.first, key.second}).add_points(pts, t);
    // A view every view_spacing seconds (unset: from the session's span so far).
    if (t - last_view_time_ >= view_spacing_at(config_, t - session_offset_)) {
        last_view_time_ = t;
        ++session_views_;
        View v;
        v.id = next_view_++;
        v.session = session_;
        v.map_time = t;
        v.T_world_sensor = T_world_sensor;
        // The world's vertical in the sensor frame: the horizon of the range image's sky.
        const Eigen::Vector3f up =
            (T_world_sensor.linear().transpose() * Eigen::Vector3d::UnitZ()).cast<float>();
        v.image = RangeImage(config_.range_image, points, up);
        pending_.push_back(std::move(v));
    }
    while (!pending_.empty() && pending_.front().map_time < now_ - config_.view_delay) {
        judge(pending_.front());
        pending_.pop_front();
    }
}

void LongTermMap::judge(const View& view) {
    const auto t0 = std::chrono::steady_clock::now();
    const Eigen::Vector2f s = view.T_world_sensor.translation().head<2>().cast<float>();
    const float size = float(config_.region_size), reach = float(config_.max_range);
    for (auto& [key, map] : regions_) {  // regions whose square comes within max_range
        const Eigen::Vector2f lo = Eigen::Vector2f(float(key.first), float(key.second)) * size;
        const Eigen::Vector2f nearest = s.cwiseMax(lo).cwiseMin(lo + Eigen::Vector2f(size, size));
        if ((nearest - s).norm() > reach) continue;
        map->judge(view);
        dirty_.insert(key);
    }
    ++views_;
    judge_ms_ +=
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

void LongTermMap::flush_views() {
    while (!pending_.empty()) {
        judge(pending_.front());
        pending_.pop_front();
    }
}

ChangeSet LongTermMap::maintain(const std::function<void()>& between) {
    ChangeSet all;
    all.session = session_;
    all.map_time = now_;
    all.voxel_size = float(config_.voxel_size);
    const MaintenanceConfig decision = decision_config();
    bool first = true;
    for (const std::pair<int, int>& key : dirty_) {  // the regions a view judged since the last
        const auto it = regions_.find(key);          // pass: nothing changed in the others
        if (it == regions_.end()) continue;
        if (!first && between) between();
        first = false;
        all.append(
            maintain_region(decision, *it->second, session_, now_, session_offset_, &next_change_));
    }
    dirty_.clear();
    return all;
}

MaintenanceConfig LongTermMap::decision_config() const {
    return resolve_thresholds(config_, SessionSeen{now_ - session_offset_, session_views_});
}

ChangeSet LongTermMap::end_session() {
    flush_views();
    ChangeSet c = maintain();
    in_session_ = false;
    return c;
}

const ObservedVoxel* LongTermMap::voxel_at(const Eigen::Vector3f& p) const {
    const Eigen::Vector2i r = region_of(p);
    const auto it = regions_.find({r.x(), r.y()});
    if (it == regions_.end()) return nullptr;
    const std::uint32_t i = it->second->find(p);
    return i == ObservationMap::kNone ? nullptr : &it->second->voxel(i);
}

bool LongTermMap::keeps(const Eigen::Vector3f& p) const { return voxel_at(p) != nullptr; }

std::vector<Eigen::Vector3f> LongTermMap::voxel_centres() const {
    std::vector<Eigen::Vector3f> out;
    for (const auto& [key, map] : regions_)
        for (std::uint32_t i = 0; i < map->size(); ++i) out.push_back(map->centre(i));
    return out;
}

LongTermMapStats LongTermMap::stats() const {
    LongTermMapStats s;
    s.regions = regions_.size();
    for (const auto& [key, map] : regions_) {
        s.voxels += map->size();
        s.memory_bytes += map->memory_bytes();
    }
    for (const View& v : pending_) s.memory_bytes += v.image.memory_bytes();
    s.views = views_;
    s.views_pending = pending_.size();
    s.judge_ms = judge_ms_;
    return s;
}

}  // namespace ltm::maintenance
