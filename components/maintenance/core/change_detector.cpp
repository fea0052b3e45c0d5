#include "maintenance/core/change_detector.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <unordered_set>

#include "maintenance/core/ground.hpp"
#include "maintenance/core/reach_down.hpp"
#include "maintenance/core/segmentation.hpp"

namespace ltm::maintenance {

namespace {

// The first (from_start) or last `n` observations of `views`.
const SlotHistogram& one_sided(const SlotHistogram& views, std::uint32_t n, bool from_start,
                               SlotHistogram& out) {
    out.clear();
    std::uint32_t left = n;
    if (from_start) {
        for (std::size_t k = 0; k < views.size() && left > 0; ++k) {
            const std::uint32_t take = std::min<std::uint32_t>(left, views[k].count);
            out.push_back({views[k].slot, std::uint16_t(take)});
            left -= take;
        }
    } else {
        for (std::size_t k = views.size(); k-- > 0 && left > 0;) {
            const std::uint32_t take = std::min<std::uint32_t>(left, views[k].count);
            out.push_back(SlotCount{views[k].slot, std::uint16_t(take)});
            left -= take;
        }
        std::reverse(out.begin(), out.end());
    }
    return out;
}

}  // namespace

VoxelJudgement judge_voxel(const ChangeConfig& config, double slot, const ObservedVoxel& voxel) {
    VoxelJudgement j;
    // Kept per thread: a pass judges every voxel of its region (no allocation a voxel).
    thread_local SlotHistogram hits, views, side;
    voxel.history.histograms(&hits, &views);
    j.views = histogram_total(views);
    j.hits = histogram_total(hits);
    // Keys left unset here (a config not resolved by resolve_thresholds): a long session.
    const auto min_views = std::uint32_t(config.min_views.value_or(kLongSession.min_views));
    const double static_span = config.static_span.value_or(kLongSession.static_span);
    const double free_dominant = config.free_dominant.value_or(kLongSession.free_dominant);
    const double changed_score = config.changed_score.value_or(kLongSession.changed_score);
    if (j.views < min_views || views.empty()) return j;
    j.last_view_slot = views.back().slot;
    const std::int32_t recent_from =
        views.back().slot - std::int32_t(std::ceil(config.recent_window / slot));
    for (const SlotCount& e : views)
        if (e.slot >= recent_from) j.recent_views += e.count;
    for (const SlotCount& e : hits)
        if (e.slot >= recent_from) j.recent_hits += e.count;
    const double free_fraction = 1.0 - double(j.hits) / double(j.views);
    if (j.hits > 0 && free_fraction >= config.min_free_fraction) {
        const double sigma = config.sigma.value_or(kLongSession.sigma) / slot;
        const double w = histogram_wasserstein1(hits, views, sigma);
        const double w_first =
            histogram_wasserstein1(one_sided(views, j.hits, true, side), views, sigma);
        const double w_last =
            histogram_wasserstein1(one_sided(views, j.hits, false, side), views, sigma);
        const double w_max = std::max(w_first, w_last);
        j.score = w_max > 1e-9 ? std::clamp(w / w_max, 0.0, 1.0) : 0.0;
    }
    const bool recent_known = j.recent_views >= std::uint32_t(config.min_recent_views);
    const double recent_hit_fraction =
        j.recent_views > 0 ? double(j.recent_hits) / double(j.recent_views) : 0.0;
    const bool changed = j.score >= changed_score ||
                         (j.hits > 0 && free_fraction >= free_dominant && free_dominant < 1.0);
    // Missing from the recent views although there before them (hit at least min_recent_views
    // times earlier): gone, whatever W1 says (a short later visit weighs little in it).
    const bool gone_now = recent_known && recent_hit_fraction <= config.gone_hit_fraction;
    if (changed && recent_known && recent_hit_fraction >= config.new_hit_fraction) {
        j.verdict = Verdict::kNew;
    } else if ((changed && !(recent_known && recent_hit_fraction >= config.new_hit_fraction)) ||
               (gone_now && j.hits - j.recent_hits >= std::uint32_t(config.min_recent_views))) {
        const double span = voxel.history.hit_span() * slot;
        j.verdict = span <= config.moving_span ? Verdict::kMoving : Verdict::kVanished;
    } else if (!hits.empty() && voxel.history.hit_span() * slot >= static_span) {
        j.verdict = Verdict::kStatic;
    }
    return j;
}

namespace {

// Per segment: its judged voxels and their verdicts.
struct Tally {
    std::uint32_t judged = 0, moving = 0, vanished = 0, fresh = 0;
    std::uint32_t gone_before = 0;  // gone voxels first seen in an earlier session
    double score = 0.0;
};

// The verdicts of a region's voxels, tallied per segment.
struct RegionJudgement {
    std::vector<VoxelJudgement> judged;  // by voxel
    std::vector<bool> stale;             // by voxel
    std::vector<bool> tracked;           // by voxel: seen moving by the motion tracker
    std::vector<bool> through;           // by voxel: gone, hit before, seen through this session
    std::vector<Tally> tally;            // by segment
    std::size_t voxels_judged = 0;
};

// What a pass removes and adds: by voxel, and each segment's gone and added voxels.
struct RegionChanges {
    std::vector<bool> remove;
    std::vector<SegmentChange> gone, added;
};

// Segments of the voxels that are not ground (labelled 1..N; ground and unclustered: 0); N.
std::uint32_t label_segments(const SegmentationConfig& config, ObservationMap& map) {
    std::vector<std::uint32_t> members;
    std::vector<Eigen::Vector3f> centres;
    for (std::uint32_t i = 0; i < map.size(); ++i) {
        map.voxel(i).segment = 0;
        if (map.voxel(i).flags & kGround) continue;
        members.push_back(i);
        centres.push_back(map.centre(i));
    }
    const Segmentation seg = euclidean_segments(config, centres);
    for (std::size_t k = 0; k < members.size(); ++k) map.voxel(members[k]).segment = seg.label[k];
    return seg.segments;
}

// Gone, hit by an earlier session and never by this one, which saw through it in at least
// through_views recent views, none a hit: the place is empty now, whatever the segment it was
// joined to (a fence segment taken down beside the fence left standing).
bool seen_through_now(const ChangeConfig& config, const ObservedVoxel& v, const VoxelJudgement& j,
                      double session_start) {
    return config.through_views > 0 && j.verdict == Verdict::kVanished && j.recent_hits == 0 &&
           j.recent_views >= std::uint32_t(config.through_views) && j.hits > 0 &&
           v.last_point() < session_start;
}

// Verdicts of the voxels, tallied per segment.
RegionJudgement judge_region(const MaintenanceConfig& config, const ObservationMap& map,
                             std::uint32_t segments, double session_start) {
    RegionJudgement out;
    std::vector<VoxelJudgement>& judged = out.judged;
    judged.resize(map.size());
    out.tally.resize(segments + 1);
    std::vector<std::int32_t> latest(segments + 1, std::numeric_limits<std::int32_t>::min());
    for (std::uint32_t i = 0; i < map.size(); ++i) {
        judged[i] = judge_voxel(config.change, config.slot, map.voxel(i));
        if (judged[i].views > 0) {
            std::int32_t& l = latest[map.voxel(i).segment];
            l = std::max(l, judged[i].last_view_slot);
        }
    }
    const auto recent_slots = std::int32_t(std::ceil(config.change.recent_window / config.slot));
    std::int32_t region_latest = std::numeric_limits<std::int32_t>::min();
    for (std::int32_t l : latest) region_latest = std::max(region_latest, l);
    out.stale.assign(map.size(), false);
    out.tracked.assign(map.size(), false);
    out.through.assign(map.size(), false);
    for (std::uint32_t i = 0; i < map.size(); ++i) {
        VoxelJudgement& j = judged[i];
        out.through[i] = seen_through_now(config.change, map.voxel(i), j, session_start);
        // Seen moving (motion_tracker.hpp), not ground, and not hit for long: moving, whatever
        // its history says (a walker's voxels are hit in nearly every view of a second).
        const ObservedVoxel& v = map.voxel(i);
        if (config.motion.enabled && (v.flags & kMoving) && !(v.flags & kGround) &&
            double(v.history.hit_span()) * config.slot <= config.motion.max_hit_span) {
            out.tracked[i] = true;
            if (j.verdict != Verdict::kVanished) j.verdict = Verdict::kMoving;
        }
        const std::uint32_t s = map.voxel(i).segment;
        if (s != 0 && (j.views == 0 || j.last_view_slot < region_latest - recent_slots)) {
            out.stale[i] = true;  // its verdict votes, but a gone segment takes it along
        }
        if (j.verdict == Verdict::kUnjudged) continue;
        ++out.voxels_judged;
        Tally& t = out.tally[map.voxel(i).segment];
        ++t.judged;
        t.score += j.score;
        t.moving += j.verdict == Verdict::kMoving ? 1 : 0;
        t.vanished += j.verdict == Verdict::kVanished ? 1 : 0;
        t.fresh += j.verdict == Verdict::kNew ? 1 : 0;
        if ((j.verdict == Verdict::kMoving || j.verdict == Verdict::kVanished) &&
            map.voxel(i).created() < session_start)
            ++t.gone_before;
    }
    return out;
}

// Segments that appeared in this session on a place an earlier session mapped (its ground
// columns hold older voxels): new objects, even though no view saw through them before they
// came (their voxels did not exist then).
std::vector<bool> appeared_segments(const GroundConfig& ground, const ObservationMap& map,
                                    std::uint32_t segments, double session_start,
                                    const std::vector<Tally>& tally) {
    std::vector<bool> appeared(segments + 1, false);
    const float inv = 1.0f / float(ground.column_size);
    const auto column = [&](const Eigen::Vector3f& p) {
        return (std::uint64_t(std::uint32_t(int(std::floor(p.x() * inv)))) << 32) |
               std::uint64_t(std::uint32_t(int(std::floor(p.y() * inv))));
    };
    std::unordered_set<std::uint64_t> mapped_before;
    std::vector<std::uint32_t> made_now(segments + 1, 0), made(segments + 1, 0),
        on_mapped(segments + 1, 0);
    for (std::uint32_t i = 0; i < map.size(); ++i) {
        const ObservedVoxel& v = map.voxel(i);
        if (v.created() < session_start) mapped_before.insert(column(map.centre(i)));
    }
    for (std::uint32_t i = 0; i < map.size(); ++i) {
        const ObservedVoxel& v = map.voxel(i);
        if (v.segment == 0) continue;
        ++made[v.segment];
        if (v.created() >= session_start) ++made_now[v.segment];
        if (mapped_before.count(column(map.centre(i)))) ++on_mapped[v.segment];
    }
    for (std::uint32_t s = 1; s <= segments; ++s)
        appeared[s] = !mapped_before.empty() && made_now[s] * 10 >= made[s] * 9 &&
                      on_mapped[s] * 2 >= made[s] && tally[s].judged > 0;
    return appeared;
}

// Voxel i joins change c (its box, its times, its centre).
void note(const ObservationMap& map, std::uint32_t i, SegmentChange& c) {
    const Eigen::Vector3f p = map.centre(i);
    if (c.voxels.empty()) {
        c.bbox_min = c.bbox_max = p;
        c.first_seen = map.voxel(i).created();
        c.last_seen = map.voxel(i).last_point();
    }
    c.bbox_min = c.bbox_min.cwiseMin(p);
    c.bbox_max = c.bbox_max.cwiseMax(p);
    c.first_seen = std::min(c.first_seen, map.voxel(i).created());
    c.last_seen = std::max(c.last_seen, map.voxel(i).last_point());
    c.voxels.push_back(p);
}

// Per voxel, from its verdict and its segment's (segment 0: ground and unclustered voxels,
// judged voxel by voxel only): removed, or marked new (kNew).
RegionChanges decide_voxels(const ChangeConfig& config, ObservationMap& map,
                            const RegionJudgement& judgement, const std::vector<bool>& appeared) {
    RegionChanges out;
    out.remove.assign(map.size(), false);
    out.gone.resize(judgement.tally.size());
    out.added.resize(judgement.tally.size());
    for (std::uint32_t i = 0; i < map.size(); ++i) {
        ObservedVoxel& v = map.voxel(i);
        const std::uint32_t s = v.segment;
        const Tally& t = judgement.tally[s];
        const Verdict verdict = judgement.judged[i].verdict;
        const bool voxel_gone = verdict == Verdict::kMoving || verdict == Verdict::kVanished;
        const bool segment_gone =
            s != 0 && t.judged > 0 &&
            double(t.moving + t.vanished) >= config.segment_fraction * double(t.judged);
        const bool segment_new =
            s != 0 && t.judged > 0 && !segment_gone &&
            (double(t.fresh) >= config.segment_fraction * double(t.judged) || appeared[s]);
        // Stale voxels go only with what was there with them (a vanished object), never with
        // a passer-by of this session that touched them.
        const bool vanished_segment = 2 * t.gone_before >= t.moving + t.vanished;
        const bool is_ground = (v.flags & kGround) != 0;
        if (!is_ground && ((segment_gone && (voxel_gone || verdict == Verdict::kUnjudged ||
                                             (judgement.stale[i] && vanished_segment))) ||
                           (voxel_gone && (config.voxel_level || s == 0 || judgement.tracked[i] ||
                                           judgement.through[i] ||
                                           judgement.judged[i].score >= config.voxel_score)))) {
            out.remove[i] = true;
            note(map, i, out.gone[s]);
        } else if (segment_new && !voxel_gone) {
            if (!(v.flags & kNew)) note(map, i, out.added[s]);
            v.flags = std::uint8_t(v.flags | kNew);
        }
    }
    return out;
}

// The segments' changes into out, in segment order (gone before added), with their reasons
// and scores.
void collect_changes(const std::vector<Tally>& tally, double session_start, RegionChanges* changes,
                     ChangeSet* out) {
    for (std::uint32_t s = 0; s < tally.size(); ++s) {
        const Tally& t = tally[s];
        const double score = t.judged > 0 ? t.score / double(t.judged) : 0.0;
        if (!changes->gone[s].voxels.empty()) {
            SegmentChange& c = changes->gone[s];
            c.reason = t.vanished > t.moving || c.first_seen < session_start
                           ? ChangeReason::kVanished
                           : ChangeReason::kMoving;
            c.score = score;
            c.judged = t.judged;
            out->voxels_removed += c.voxels.size();
            out->changes.push_back(std::move(c));
        }
        if (!changes->added[s].voxels.empty()) {
            SegmentChange& c = changes->added[s];
            c.reason = ChangeReason::kNew;
            c.score = score;
            c.judged = t.judged;
            out->changes.push_back(std::move(c));
        }
    }
}

// Ids from *next_id (advanced), the region, centroids.
void number_changes(const Eigen::Vector2i& region, std::vector<SegmentChange>* changes,
                    std::uint64_t* next_id) {
    for (SegmentChange& c : *changes) {
        c.id = (*next_id)++;
        c.region = region;
        Eigen::Vector3f sum = Eigen::Vector3f::Zero();
        for (const Eigen::Vector3f& p : c.voxels) sum += p;
        c.centroid = sum / float(c.voxels.size());
    }
}

}  // namespace

ChangeSet maintain_region(const MaintenanceConfig& config, ObservationMap& map,
                          std::uint32_t session, double map_time, double session_start,
                          std::uint64_t* next_id, const std::function<void()>& between) {
    const auto t0 = std::chrono::steady_clock::now();
    const auto pause = [&between] {
        if (between) between();
    };
    ChangeSet out;
    out.session = session;
    out.map_time = map_time;
    out.voxel_size = map.voxel_size();
    out.voxels_before = map.size();
    if (map.empty()) return out;
    out.ground_voxels = mark_ground(config.ground, map);
    pause();
    const std::uint32_t segments = label_segments(config.segmentation, map);
    out.segments = segments;
    pause();
    const RegionJudgement judgement = judge_region(config, map, segments, session_start);
    pause();
    out.voxels_judged = judgement.voxels_judged;
    const std::vector<bool> appeared =
        appeared_segments(config.ground, map, segments, session_start, judgement.tally);
    RegionChanges changes = decide_voxels(config.change, map, judgement, appeared);
    for (const std::uint32_t b : reach_down(config, map, session_start, &changes.remove))
        note(map, b, changes.gone[map.voxel(b).segment]);
    collect_changes(judgement.tally, session_start, &changes, &out);
    number_changes(map.region(), &out.changes, next_id);
    map.erase(changes.remove);
    out.time_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return out;
}

}  // namespace ltm::maintenance
