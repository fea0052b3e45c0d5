#include "evaluation/core/dynamic_removal.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "evaluation/core/point_grid.hpp"

namespace ltm::eval {

bool append_labelled_scan(const common::PointCloud& cloud, const std::vector<std::uint32_t>& labels,
                          const Eigen::Isometry3d& T_world_sensor, common::LabelScheme scheme,
                          bool changed_is_dynamic, double max_range, std::uint32_t frame,
                          LabelledMap& map) {
    if (labels.size() != cloud.size()) return false;
    const Eigen::Isometry3f T = T_world_sensor.cast<float>();
    const double max_r2 = max_range * max_range;
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const Eigen::Vector3f& p = cloud.points[i];
        if (!p.allFinite()) continue;
        if (max_range > 0.0 && p.cast<double>().squaredNorm() > max_r2) continue;
        map.points.push_back(T * p);
        map.dynamic.push_back(common::is_dynamic_label(labels[i], scheme, changed_is_dynamic) ? 1
                                                                                              : 0);
        map.labels.push_back(labels[i]);
        map.frames.push_back(frame);
    }
    return true;
}

namespace {

double percent(std::size_t part, std::size_t whole) {
    return whole > 0 ? 100.0 * static_cast<double>(part) / static_cast<double>(whole) : 0.0;
}

struct ObjectPoints {
    std::size_t points = 0, removed = 0;
    std::map<std::uint16_t, std::size_t> classes;                             // class -> points
    std::map<std::uint32_t, std::pair<Eigen::Vector3d, std::size_t>> frames;  // frame -> sum, n
};

// Per dynamic object, from the per-point labels, frames and kept flags; adds the moving-object
// totals to r.
void score_objects(const LabelledMap& truth, const std::vector<std::uint8_t>& kept,
                   double min_travel, DynamicRemovalResult& r) {
    const std::size_t n = kept.size();
    if (truth.labels.size() < n || truth.frames.size() < n) return;
    // Key: instance id then class, instance 0 last.
    std::map<std::uint64_t, ObjectPoints> objects;
    for (std::size_t i = 0; i < n; ++i) {
        if (!truth.dynamic[i]) continue;
        const std::uint16_t id = common::label_object_id(truth.labels[i]);
        const std::uint16_t cls = common::label_class(truth.labels[i]);
        ObjectPoints& o = objects[(std::uint64_t{id == 0} << 32) | (std::uint64_t{id} << 16) | cls];
        ++o.points;
        if (!kept[i]) ++o.removed;
        auto& f = o.frames.try_emplace(truth.frames[i], Eigen::Vector3d::Zero(), 0).first->second;
        f.first += truth.points[i].cast<double>();
        ++f.second;
    }
    for (const auto& [key, o] : objects) {
        DynamicObject d;
        d.instance = static_cast<std::uint16_t>(key >> 16);
        d.label_class = static_cast<std::uint16_t>(key);
        const auto& first = *o.frames.begin();
        const auto& last = *o.frames.rbegin();
        d.first_frame = first.first;
        d.last_frame = last.first;
        d.frames = o.frames.size();
        d.points = o.points;
        d.removed = o.removed;
        d.removed_pct = percent(o.removed, o.points);
        d.travel = (last.second.first / static_cast<double>(last.second.second) -
                    first.second.first / static_cast<double>(first.second.second))
                       .norm();
        if (d.travel >= min_travel) {
            ++r.moving_objects;
            r.moving_points += d.points;
            r.moving_removed += d.removed;
        }
        r.objects.push_back(d);
    }
    r.moving_da_pct = percent(r.moving_removed, r.moving_points);
}

}  // namespace

DynamicRemovalResult evaluate_dynamic_removal(const LabelledMap& truth,
                                              const std::vector<Eigen::Vector3f>& output_map,
                                              const DynamicRemovalConfig& config) {
    const PointGrid grid(output_map, config.match_distance);
    DynamicRemovalResult r;
    const std::size_t n = std::min(truth.points.size(), truth.dynamic.size());
    std::vector<std::uint8_t> kept_flags(n);
    for (std::size_t i = 0; i < n; ++i) {
        const bool kept = grid.has_neighbour(truth.points[i]);
        kept_flags[i] = kept ? 1 : 0;
        if (truth.dynamic[i]) {
            ++r.dynamic_points;
            if (!kept) ++r.dynamic_removed;
        } else {
            ++r.static_points;
            if (kept) ++r.static_kept;
        }
    }
    r.sa_pct = percent(r.static_kept, r.static_points);
    r.da_pct = percent(r.dynamic_removed, r.dynamic_points);
    r.aa_pct = std::sqrt(r.sa_pct * r.da_pct);
    if (r.sa_pct + r.da_pct > 0.0) r.ha_pct = 2.0 * r.sa_pct * r.da_pct / (r.sa_pct + r.da_pct);
    score_objects(truth, kept_flags, config.min_travel, r);
    if (truth.labels.size() >= n) {  // static points lost, per object
        std::map<std::uint32_t, std::pair<std::size_t, std::size_t>> lost;  // label: points, lost
        for (std::size_t i = 0; i < n; ++i) {
            if (truth.dynamic[i]) continue;
            auto& l = lost[truth.labels[i]];
            ++l.first;
            if (!kept_flags[i]) ++l.second;
        }
        for (const auto& [label, l] : lost) {
            if (l.second == 0) continue;
            DynamicObject d;
            d.instance = common::label_object_id(label);
            d.label_class = common::label_class(label);
            d.points = l.first;
            d.removed = l.second;
            d.removed_pct = percent(l.second, l.first);
            r.static_losses.push_back(d);
        }
        std::sort(
            r.static_losses.begin(), r.static_losses.end(),
            [](const DynamicObject& a, const DynamicObject& b) { return a.removed > b.removed; });
        if (r.static_losses.size() > 10) r.static_losses.resize(10);
    }
    return r;
}

}  // namespace ltm::eval
