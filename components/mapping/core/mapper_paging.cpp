// Paging the local maps (issue 28 item 3; mapper.hpp, PagingConfig): the keyframes, their
// descriptors and the pose graph stay; a local map's voxels leave memory when it lies far from
// every open session's newest keyframe and a save holds it unchanged, and come back from that
// file when a loop's verification, a fold or a maintenance edit needs them.
//
// The local maps are shared and immutable (a save's snapshot holds them): paging out drops the
// Mapper's reference only (a snapshot still writing keeps its own), and a map loaded back is
// complete before the Mapper holds it, so no thread sees a half-loaded or freed map.
#include <algorithm>
#include <limits>

#include "common/core/io_error.hpp"
#include "mapping/core/mapper.hpp"

namespace ltm::mapping {

namespace {

// A local map's fields without its voxels and stamps (what a paged-out map answers from).
std::shared_ptr<const common::LocalMapData> header_of(const common::LocalMapData& m) {
    auto h = std::make_shared<common::LocalMapData>();
    h->id = m.id;
    h->revision = m.revision;
    h->finished = m.finished;
    h->segment = m.segment;
    h->T_odom_anchor = m.T_odom_anchor;
    h->T_anchor_grid = m.T_anchor_grid;
    h->bbox_min = m.bbox_min;
    h->bbox_max = m.bbox_max;
    h->voxel_size = m.voxel_size;
    return h;
}

}  // namespace

std::size_t Mapper::page_out(
    const std::unordered_map<std::uint64_t, map::MapWriter::WrittenLocalMap>& written) {
    const double radius = config_.paging.radius;
    if (!loader_ || radius <= 0.0) return 0;
    std::vector<Eigen::Vector3d> robots;
    for (const auto& [id, live] : live_) {
        if (live.position) robots.push_back(*live.position);
    }
    if (robots.empty()) return 0;  // nowhere yet: everything may be needed
    std::size_t count = 0;
    for (auto& [id, e] : maps_) {
        if (!e.stored.data) continue;
        const map::PoseGraphNode* node = graph_.find(id);
        if (!node) continue;
        const common::LocalMapData& m = *e.stored.data;
        if (is_open(node->session) && !m.finished) continue;  // still being built
        if (std::find(removal_waiting_.begin(), removal_waiting_.end(), id) !=
            removal_waiting_.end())
            continue;  // an edit waits for it
        const auto w = written.find(id);
        if (w == written.end() || !w->second.file || w->second.data.lock() != e.stored.data)
            continue;  // not on disk as it is now
        // By its anchor (where it started; its voxels reach a sensor's range around).
        const Eigen::Vector3d anchor = node->T_world_anchor.translation();
        double nearest = std::numeric_limits<double>::infinity();
        for (const Eigen::Vector3d& p : robots) nearest = std::min(nearest, (anchor - p).norm());
        if (nearest <= radius) continue;
        e.header = header_of(m);
        e.stored.paged = w->second.file;
        e.stored.data.reset();
        verifier_.forget(e.serial);  // its loop target's grids leave with it
        ++count;
    }
    return count;
}

std::size_t Mapper::paged_out() const {
    std::size_t n = 0;
    for (const auto& [id, e] : maps_) n += e.stored.data ? 0 : 1;
    return n;
}

std::vector<std::string> Mapper::take_paging_problems() {
    std::vector<std::string> out;
    out.swap(paging_problems_);
    return out;
}

bool Mapper::page_in(std::uint64_t node, MapEntry& e) {
    if (e.stored.data) return true;
    if (e.unavailable) return false;
    std::shared_ptr<const common::LocalMapData> data = content(node, e);
    if (!data) {
        e.unavailable = true;  // stays on disk as it was; a save keeps its file
        return false;
    }
    e.stored.data = std::move(data);
    e.stored.paged.reset();
    e.header.reset();
    ++paged_in_;
    return true;
}

std::shared_ptr<const common::LocalMapData> Mapper::content(std::uint64_t node,
                                                            const MapEntry& e) const {
    if (e.stored.data) return e.stored.data;
    if (e.unavailable || !e.stored.paged || !loader_) return nullptr;
    const auto fail = [&](const std::string& why) {
        paging_problems_.push_back("local map of node " + std::to_string(node) +
                                   " unavailable (kept on disk as it was): " + why);
        return nullptr;
    };
    try {
        std::shared_ptr<const common::LocalMapData> data = loader_(*e.stored.paged);
        if (!data) return fail("not loaded");
        // The file a save wrote of this map: the same map, or it is not ours.
        if (data->id != e.header->id || data->revision != e.header->revision)
            return fail(e.stored.paged->file + ": holds local map " + std::to_string(data->id) +
                        " revision " + std::to_string(data->revision) + ", expected " +
                        std::to_string(e.header->id) + " revision " +
                        std::to_string(e.header->revision));
        return data;
    } catch (const std::exception& error) {
        return fail(error.what());
    }
}

map::MapData Mapper::complete_snapshot() const {
    map::MapData m = snapshot();
    for (map::StoredLocalMap& s : m.local_maps) {
        if (s.data) continue;
        const auto it = maps_.find(s.node);
        std::shared_ptr<const common::LocalMapData> data =
            it == maps_.end() ? nullptr : content(s.node, it->second);
        if (!data) {
            throw common::IoError(s.paged ? s.paged->file : "local map",
                                  "the local map of node " + std::to_string(s.node) +
                                      " cannot be read back for this save");
        }
        s.data = std::move(data);
        s.paged.reset();
    }
    return m;
}

}  // namespace ltm::mapping
