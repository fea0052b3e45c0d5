// The Mapper's ties to a loaded map and its edits by map maintenance (see mapper.hpp):
// localisation fixes as edges from the loaded map (add_map_fix), and the cells maintenance found
// emptied cleared from the local maps (remove_cells, keep_cells). One concept: what the map
// learns from the rest of the robot, beside its own odometry and loops.
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "common/core/column_floor.hpp"
#include "mapping/core/mapper.hpp"

namespace ltm::mapping {
namespace {

double angle_deg(const Eigen::Matrix3d& R) { return Eigen::AngleAxisd(R).angle() * 180.0 / M_PI; }

}  // namespace

MapFixResult Mapper::add_map_fix(std::uint32_t session, std::uint64_t local_map_id,
                                 const Eigen::Isometry3d& T_anchor_lidar,
                                 const Eigen::Isometry3d& T_world_lidar,
                                 std::uint32_t keyframe_index) {
    MapFixResult r;
    if (!config_.map_fix.enabled) {
        r.message = "map fixes are off (map_fix.enabled)";
        return r;
    }
    if (!is_open(session)) {
        r.message = "session " + std::to_string(session) + " is not open";
        return r;
    }
    if (!T_world_lidar.matrix().allFinite() || !T_anchor_lidar.matrix().allFinite()) {
        r.message = "the fix is not a finite pose";
        return r;
    }
    if (folding_.find(session, local_map_id)) {
        r.message = "local map " + std::to_string(local_map_id) + " was folded into the map";
        return r;
    }
    const std::optional<std::uint64_t> node = node_of(local_map_id, session);
    const map::PoseGraphNode* n = node ? graph_.find(*node) : nullptr;
    if (!n || n->fixed || n->session != session) {
        r.message = "local map " + std::to_string(local_map_id) + " has no node of its own yet";
        return r;
    }
    if (fixes_per_node_[*node] >= config_.map_fix.per_local_map) {
        r.message = "local map " + std::to_string(local_map_id) + " has its fixes already";
        return r;
    }
    // The nearest keyframe of a loaded (not open) session: the edge's other end.
    std::optional<std::uint32_t> nearest;
    double best = config_.map_fix.radius * config_.map_fix.radius;
    for (std::uint32_t i = 0; i < keyframes_.size(); ++i) {
        const map::StoredKeyframe& k = *keyframes_[i];
        if (is_open(k.session)) continue;
        const map::PoseGraphNode* kn = graph_.find(k.node);
        if (!kn) continue;
        const double d2 = ((kn->T_world_anchor * k.data.T_anchor_lidar).translation() -
                           T_world_lidar.translation())
                              .squaredNorm();
        if (d2 <= best) {
            best = d2;
            nearest = i;
        }
    }
    if (!nearest) {
        r.message = "no keyframe of the loaded map within map_fix.radius of the fix";
        return r;
    }
    const map::StoredKeyframe& match = *keyframes_[*nearest];
    map::PoseGraphEdge e;
    e.from = match.node;
    e.to = *node;
    e.kind = map::EdgeKind::kLoop;
    const Eigen::Isometry3d T_world_anchor = T_world_lidar * T_anchor_lidar.inverse();
    e.T_from_to = graph_.find(e.from)->T_world_anchor.inverse() * T_world_anchor;
    e.information = loop_information(config_.loop_edge);
    e.query_keyframe = keyframe_index;
    e.match_keyframe = *nearest;
    const Eigen::Isometry3d predicted =
        graph_.find(e.from)->T_world_anchor.inverse() * n->T_world_anchor;
    const Eigen::Isometry3d D = predicted.inverse() * e.T_from_to;
    r.disagreement = D.translation().norm();
    const double disagreement_deg = angle_deg(D.linear());
    const bool placed = segments_.root(graph_, e.from) == segments_.root(graph_, e.to);
    if (placed) {
        const std::string why = inconsistency(e.from, e.to, r.disagreement, disagreement_deg);
        if (!why.empty()) {
            r.message = "fix refused: " + why;
            return r;
        }
    }
    if (!graph_.add_edge(e)) {
        r.message = "the edge could not be added";
        return r;
    }
    if (!placed) align_parts(e);
    r.added = true;
    r.placed_part = !placed;
    r.from_node = e.from;
    r.to_node = e.to;
    r.optimisation_due = !placed || r.disagreement > config_.long_term.agree_translation ||
                         disagreement_deg > config_.long_term.agree_rotation;
    due_loops_ += r.optimisation_due ? 1 : 0;
    ++fixes_per_node_[*node];
    ++map_fixes_;
    std::ostringstream m;
    m << "local map " << local_map_id << " tied to the map at keyframe " << keyframe_index
      << (placed ? "" : " (its part placed by it)") << ", " << r.disagreement
      << " m from the graph's estimate";
    r.message = m.str();
    return r;
}

// The ground guard (MapEditConfig::ground_height): of the `flat` voxels (dropped, on a
// near-horizontal plane), those within ground_height of the lowest voxel centre within
// ground_reach are ground and stay. Columns of 1 m; a voxel's lowest is looked for in the columns
// whose cells lie within ground_reach of its own.
void Mapper::keep_ground(const common::LocalMapData& map, const Eigen::Isometry3f& T,
                         const std::vector<std::size_t>& flat, std::vector<char>& drop) const {
    constexpr float kColumn = 1.0f;
    common::ColumnFloor floor(kColumn, map.voxels.size() / 2);
    for (const common::VoxelData& v : map.voxels) floor.add(T * v.centre);
    const MapEditConfig& edits = config_.map_edits;
    const int cells = int(std::ceil(edits.ground_reach / kColumn));
    for (const std::size_t i : flat) {
        const Eigen::Vector3f p = T * map.voxels[i].centre;
        if (p.z() - floor.lowest_around(p, cells) <= float(edits.ground_height)) drop[i] = 0;
    }
}

std::shared_ptr<const common::LocalMapData> Mapper::without_removed(
    const common::LocalMapData& map, const Eigen::Isometry3d& T_world_anchor,
    std::size_t* removed) const {
    *removed = 0;
    if (removed_.empty()) return nullptr;
    const Eigen::Isometry3f T = (T_world_anchor * map.T_anchor_grid).cast<float>();
    // A voxel's points spread over its cube: its centre can lie between the surfaces it holds.
    const float reach = 0.5f * map.voxel_size;
    // A vanished object's cell on the voxel's own surface, within one voxel edge (MapEditConfig):
    // not on the ground's plane (an upright enough surface).
    const MapEditConfig& edits = config_.map_edits;
    const bool surfaces = edits.surface_band > 0.0 && !removed_.surfaces_empty();
    const float max_nz = float(std::cos(edits.surface_min_tilt * M_PI / 180.0));
    std::vector<char> drop(map.voxels.size(), 0);
    std::vector<std::size_t> flat;  // dropped voxels on a near-horizontal plane: ground?
    for (std::size_t i = 0; i < map.voxels.size(); ++i) {
        const common::VoxelData& v = map.voxels[i];
        const Eigen::Vector3f p = T * v.centre;
        const bool planar = v.normal.squaredNorm() > 0.5f;
        const Eigen::Vector3f n = planar ? Eigen::Vector3f((T.linear() * v.normal).normalized())
                                         : Eigen::Vector3f::Zero();
        bool gone = removed_.covers(p, reach);
        if (!gone && surfaces && planar)
            gone = std::abs(n.z()) < max_nz &&
                   removed_.surface_near(p, n, map.voxel_size, float(edits.surface_band));
        if (gone) {
            drop[i] = 1;
            if (planar && std::abs(n.z()) >= max_nz) flat.push_back(i);
        }
    }
    if (edits.ground_height > 0.0 && !flat.empty()) keep_ground(map, T, flat, drop);
    *removed = static_cast<std::size_t>(std::count(drop.begin(), drop.end(), char(1)));
    if (*removed == 0) return nullptr;
    auto out = std::make_shared<common::LocalMapData>();
    out->id = map.id;
    out->revision = map.revision;
    out->finished = map.finished;
    out->segment = map.segment;
    out->T_odom_anchor = map.T_odom_anchor;
    out->T_anchor_grid = map.T_anchor_grid;
    out->bbox_min = map.bbox_min;
    out->bbox_max = map.bbox_max;
    out->voxel_size = map.voxel_size;
    out->observation_times = map.observation_times;
    out->voxels.reserve(map.voxels.size() - *removed);
    for (std::size_t i = 0; i < map.voxels.size(); ++i) {
        if (!drop[i]) out->voxels.push_back(map.voxels[i]);
    }
    return out;
}

bool Mapper::on_reference_part(std::uint64_t node) const {
    return segments_.root(graph_, node) == segments_.root(SegmentKey(reference_session(), 0));
}

std::size_t Mapper::remove_cells(const std::vector<Eigen::Vector3f>& centres, float cell_size,
                                 const std::vector<std::vector<Eigen::Vector3f>>& vanished) {
    const std::size_t before = removed_voxels_;
    remove_cells_in_steps(centres, cell_size, vanished);
    while (clear_removed_step()) {
    }
    return removed_voxels_ - before;
}

std::size_t Mapper::remove_cells_in_steps(
    const std::vector<Eigen::Vector3f>& centres, float cell_size,
    const std::vector<std::vector<Eigen::Vector3f>>& vanished) {
    std::size_t added = removed_.add(centres, cell_size);
    for (const std::vector<Eigen::Vector3f>& segment : vanished) {
        if (segment.size() >= std::size_t(std::max(1, config_.map_edits.surface_min_cells)))
            added += removed_.add_surface(segment, cell_size);
    }
    if (added == 0) return removal_waiting_.size();
    Eigen::AlignedBox3f box;
    for (const Eigen::Vector3f& c : centres) {
        if (c.allFinite()) box.extend(c);
    }
    // (a vanished object's cell reaches the voxels on its surface within a voxel edge)
    const float grow = cell_size + (vanished.empty() ? 0.0f : 1.0f);
    box.min().array() -= grow;
    box.max().array() += grow;
    for (const auto& [id, entry] : maps_) {
        const map::PoseGraphNode* n = graph_.find(id);
        if (!n || !on_reference_part(id)) continue;   // unplaced parts: not where the cells are
        const common::LocalMapData& m = meta(entry);  // (paged out: its box; loaded to clear)
        // The map's box in the world frame: skip maps nowhere near the cells.
        const Eigen::Isometry3d T = n->T_world_anchor * m.T_anchor_grid;
        Eigen::AlignedBox3f world;
        for (int i = 0; i < 8; ++i) {
            const Eigen::Vector3d corner((i & 1) ? m.bbox_max.x() : m.bbox_min.x(),
                                         (i & 2) ? m.bbox_max.y() : m.bbox_min.y(),
                                         (i & 4) ? m.bbox_max.z() : m.bbox_min.z());
            world.extend((T * corner).cast<float>());
        }
        if (!world.intersects(box)) continue;
        // Cleared once of every cell recorded by then, however many passes listed it.
        if (std::find(removal_waiting_.begin(), removal_waiting_.end(), id) ==
            removal_waiting_.end())
            removal_waiting_.push_back(id);
    }
    return removal_waiting_.size();
}

bool Mapper::clear_removed_step(std::size_t* removed) {
    if (removed) *removed = 0;
    if (removal_waiting_.empty()) return false;
    const std::uint64_t id = removal_waiting_.front();
    removal_waiting_.pop_front();
    const auto it = maps_.find(id);
    const map::PoseGraphNode* n = graph_.find(id);
    // (a map folded away since: nothing left to clear; an unavailable one stays as on disk)
    if (it != maps_.end() && n && page_in(id, it->second)) {
        std::size_t count = 0;
        if (auto out = without_removed(*it->second.stored.data, n->T_world_anchor, &count)) {
            it->second.stored.data = std::move(out);
            it->second.serial = next_serial_++;
            ++revision_;
            removed_voxels_ += count;
            if (removed) *removed = count;
        }
    }
    return !removal_waiting_.empty();
}

void Mapper::keep_cells(const std::vector<Eigen::Vector3f>& centres, float /*cell_size*/) {
    removed_.erase(centres);
}

}  // namespace ltm::mapping
