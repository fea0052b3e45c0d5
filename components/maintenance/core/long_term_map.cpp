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
    k.require(c.motion.min_lag <= c.motion.max_lag, "motion.min_lag",
              "must not be above motion.max_lag");
    k.require(c.motion.min_cells <= c.motion.max_cells, "motion.min_cells",
              "must not be above motion.max_cells");
    return k.problem();
}

LongTermMap::LongTermMap(const MaintenanceConfig& config)
    : config_(config), motion_(config.motion, config.range_image, config.max_range) {
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
    motion_.clear();
    mapped_before_.clear();
    for (const auto& [key, r] : regions_)
        if (!r->empty()) mapped_before_.insert(key);
    if (pager_)
        for (const auto& entry : pager_->regions()) mapped_before_.insert(entry.first);
}

double LongTermMap::map_time_of(double stamp) const {
    if (!std::isfinite(stamp)) return now_;
    return session_offset_ + std::max(0.0, stamp - session_start_stamp_);
}

Eigen::Vector2i LongTermMap::region_of(const Eigen::Vector3f& p) const {
    const float inv = 1.0f / float(config_.region_size);
    return {int(std::floor(p.x() * inv)), int(std::floor(p.y() * inv))};
}

void LongTermMap::set_paging(const PagingConfig& paging) {
    if (paging.radius <= 0.0) {
        page_in_all();
        pager_.reset();
        paging_radius_ = 0.0;
        return;
    }
    if (paging.dir.empty())
        throw common::ConfigError("paging_dir", "is required with a paging radius");
    pager_ = std::make_unique<RegionPager>(paging.dir, config_);
    paging_radius_ = paging.radius;
}

ObservationMap& LongTermMap::region(const Eigen::Vector2i& key) {
    const RegionKey k{key.x(), key.y()};
    auto& slot = regions_[k];
    if (!slot) {
        slot = pager_ && pager_->holds(k) ? pager_->page_in(k)
                                          : std::make_unique<ObservationMap>(config_, key);
    }
    return *slot;
}

bool LongTermMap::within(const RegionKey& key, const Eigen::Vector2f& p, float reach) const {
    const float size = float(config_.region_size);
    const Eigen::Vector2f lo = Eigen::Vector2f(float(key.first), float(key.second)) * size;
    const Eigen::Vector2f nearest = p.cwiseMax(lo).cwiseMin(lo + Eigen::Vector2f(size, size));
    return (nearest - p).norm() <= reach;
}

void LongTermMap::page_far(const Eigen::Vector3d& sensor, const std::function<void()>& between) {
    if (!pager_) return;
    const Eigen::Vector2f p = sensor.head<2>().cast<float>();
    for (auto it = regions_.begin(); it != regions_.end();) {
        if (dirty_.count(it->first) || within(it->first, p, float(paging_radius_))) {
            ++it;
            continue;
        }
        pager_->page_out(it->first, *it->second);
        it = regions_.erase(it);
        if (between) between();
    }
}

void LongTermMap::page_in_all() {
    if (!pager_) return;
    std::vector<RegionKey> keys;
    for (const auto& entry : pager_->regions()) keys.push_back(entry.first);
    for (const RegionKey& k : keys) region({k.first, k.second});
}

void LongTermMap::add_scan(const std::vector<Eigen::Vector3f>& points,
                           const Eigen::Isometry3d& T_world_sensor, double stamp,
                           const std::function<void()>& between) {
    if (!in_session_) begin_session(session_, stamp);
    if (!T_world_sensor.matrix().allFinite()) return;
    const double t = map_time_of(stamp);
    now_ = std::max(now_, t);
    // Points to their regions.
    const Eigen::Isometry3f T = T_world_sensor.cast<float>();
    const float max_range_sq = float(config_.max_range * config_.max_range);
    const float min_range_sq = float(config_.range_image.min_range * config_.range_image.min_range);
    // Per region: the points that may create voxels anywhere, and (create_range) the far ones
    // that create none beside a voxel of an earlier session.
    const float create_range_sq = float(config_.create_range * config_.create_range);
    std::map<std::pair<int, int>, std::vector<Eigen::Vector3f>> by_region, far_by_region;
    for (const Eigen::Vector3f& p : points) {
        if (!p.allFinite()) continue;
        const float r2 = p.squaredNorm();
        if (r2 > max_range_sq || r2 < min_range_sq) continue;
        const Eigen::Vector3f q = T * p;
        const Eigen::Vector2i r = region_of(q);
        const std::pair<int, int> key{r.x(), r.y()};
        const bool far =
            config_.create_range > 0.0 && r2 > create_range_sq && mapped_before_.count(key) > 0;
        (far ? far_by_region : by_region)[key].push_back(q);
    }
    // A region paged in for the scan: `between` after it.
    const auto paced_region = [&](const std::pair<int, int>& key) -> ObservationMap& {
        const bool in_memory = regions_.count(key) > 0;
        ObservationMap& r = region({key.first, key.second});
        if (!in_memory && between) between();
        return r;
    };
    for (auto& [key, pts] : by_region) paced_region(key).add_points(pts, t);
    for (auto& [key, pts] : far_by_region) paced_region(key).add_points(pts, t, session_offset_);
    if (config_.motion.enabled && t - session_offset_ < config_.motion.session_span) {
        follow_motion(points, T_world_sensor, t);
    } else if (motion_.memory_bytes() > 0) {
        motion_.clear();  // past the session's first span: its scans are not needed any more
    }
    // A view every view_spacing seconds (unset: from the session's span so far), within 5 % of
    // it: a 10 Hz stream's stamps (a driver's jitter, or 0.1 s steps summed in floating point)
    // put the second scan at 0.2 s +- a little, which made the views come every 0.2 or 0.3 s.
    const double spacing = view_spacing_at(config_, t - session_offset_);
    if (t - last_view_time_ >= spacing - 0.05 * spacing) {
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
        judge(pending_.front(), between);
        pending_.pop_front();
    }
    page_far(T_world_sensor.translation(), between);
}

void LongTermMap::follow_motion(const std::vector<Eigen::Vector3f>& points,
                                const Eigen::Isometry3d& T_world_sensor, double map_time) {
    const auto t0 = std::chrono::steady_clock::now();
    for (const Eigen::Vector3f& p : motion_.add_scan(points, T_world_sensor, map_time)) {
        const Eigen::Vector2i r = region_of(p);
        const auto it = regions_.find({r.x(), r.y()});
        if (it == regions_.end()) continue;
        const std::uint32_t i = it->second->find(p);
        if (i == ObservationMap::kNone) continue;
        ObservedVoxel& v = it->second->voxel(i);
        if (!(v.flags & kMoving)) ++flagged_moving_;
        v.flags = std::uint8_t(v.flags | kMoving);
    }
    motion_ms_ +=
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

void LongTermMap::judge(const View& view, const std::function<void()>& between) {
    auto t0 = std::chrono::steady_clock::now();
    const Eigen::Vector2f s = view.T_world_sensor.translation().head<2>().cast<float>();
    const float reach = float(config_.max_range);
    std::vector<RegionKey> keys;  // regions whose square comes within max_range, in key order
    for (const auto& entry : regions_)
        if (within(entry.first, s, reach)) keys.push_back(entry.first);
    if (pager_) {
        for (const auto& entry : pager_->regions())
            if (within(entry.first, s, reach)) keys.push_back(entry.first);
        std::sort(keys.begin(), keys.end());
    }
    for (std::size_t i = 0; i < keys.size(); ++i) {
        region({keys[i].first, keys[i].second}).judge(view);
        dirty_.insert(keys[i]);
        if (between && i + 1 < keys.size()) {  // judge_ms_: the work, not the waits
            const auto t1 = std::chrono::steady_clock::now();
            judge_ms_ += std::chrono::duration<double, std::milli>(t1 - t0).count();
            between();
            t0 = std::chrono::steady_clock::now();
        }
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
    // The regions a view judged since the last pass (in memory: page_far keeps them there):
    // nothing changed in the others.
    for (const std::pair<int, int>& key : dirty_) {
        if (!regions_.count(key) && !(pager_ && pager_->holds(key))) continue;
        if (!first && between) between();
        first = false;
        all.append(maintain_region(decision, region({key.first, key.second}), session_, now_,
                                   session_offset_, &next_change_, between));
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
    for (const View& v : pending_) s.views_bytes += v.image.memory_bytes();
    s.motion_bytes = motion_.memory_bytes();
    s.memory_bytes += s.views_bytes + s.motion_bytes;
    s.motion_ms = motion_ms_;
    s.motion = motion_.stats();
    s.voxels_flagged_moving = flagged_moving_;
    if (pager_) {
        s.regions_paged = pager_->regions().size();
        s.voxels_paged = pager_->voxels();
        s.voxels += s.voxels_paged;
        s.regions += s.regions_paged;
        s.paged_bytes = pager_->disk_bytes();
        s.pages_out = pager_->pages_out();
        s.pages_in = pager_->pages_in();
    }
    s.views = views_;
    s.views_pending = pending_.size();
    s.judge_ms = judge_ms_;
    return s;
}

}  // namespace ltm::maintenance
