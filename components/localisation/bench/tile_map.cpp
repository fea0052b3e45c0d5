// ltm_tile_map: a larger site made from a saved map's copies side by side (issue 28 item 3: how
// the localisation's memory grows with the site's size, whole and paged). Copy k is the map moved
// by k * offset along x; its nodes, keyframes, local maps and edges get ids of their own (copy k
// adds k * 2^40). Only for measurements: the copies are not joined by any edge, and a scan of the
// original place has k + 1 look-alike places in the result (a global query there is ambiguous).
#include <Eigen/Geometry>
#include <cstdio>
#include <memory>
#include <string>

#include "common/cli/cli.hpp"
#include "common/core/io_error.hpp"
#include "map/core/map_store.hpp"

namespace {

using namespace ltm;

constexpr std::uint64_t kCopyIds = std::uint64_t(1) << 40;

}  // namespace

int main(int argc, char** argv) {
    std::string in, out;
    unsigned copies = 3;
    double offset = 1000.0;
    CLI::App app{"A larger site made from a saved map's copies side by side (measurements)",
                 "ltm_tile_map"};
    common::cli::configure(app);
    app.add_option("in", in, "the saved map directory")->required();
    app.add_option("out", out, "the new map directory (must not exist)")->required();
    app.add_option("--copies", copies, "copies of the map in the result (>= 1)");
    app.add_option("--offset", offset, "between two copies, along x [m]");
    if (const int code = common::cli::parse(app, argc, argv); code >= 0) return code;
    if (copies < 1) {
        return common::cli::usage_error(app, common::cli::UsageError("--copies", "at least 1"));
    }
    try {
        const map::LoadedMap loaded = map::load_map(in);
        for (const std::string& r : loaded.refused)
            std::fprintf(stderr, "refused: %s\n", r.c_str());
        const map::MapData& m = loaded.map;
        map::MapData t;
        t.revision = m.revision;
        t.descriptor_config = m.descriptor_config;
        t.localisation_descriptor_config = m.localisation_descriptor_config;
        t.sessions = m.sessions;
        for (unsigned k = 0; k < copies; ++k) {
            const std::uint64_t add = k * kCopyIds;
            Eigen::Isometry3d shift = Eigen::Isometry3d::Identity();
            shift.translation().x() = k * offset;
            for (map::PoseGraphNode n : m.nodes) {
                n.id += add;
                n.T_world_anchor = shift * n.T_world_anchor;
                t.nodes.push_back(n);
            }
            for (map::PoseGraphEdge e : m.edges) {
                e.from += add;
                e.to += add;
                t.edges.push_back(e);
            }
            for (const auto& kf : m.keyframes) {
                auto c = std::make_shared<map::StoredKeyframe>(*kf);
                c->node += add;
                c->data.id += add;
                c->data.local_map_id += add;
                t.keyframes.push_back(std::move(c));
            }
            for (const map::StoredLocalMap& lm : m.local_maps) {
                if (!lm.data) continue;
                auto data = std::make_shared<common::LocalMapData>(*lm.data);
                data->id += add;
                t.local_maps.push_back({lm.node + add, lm.session, std::move(data)});
            }
        }
        const map::SaveStats s = map::save_map(out, t);
        std::printf("%s: %u copies of %s, %zu nodes, %zu local maps, %zu keyframes, %.1f MB\n",
                    out.c_str(), copies, in.c_str(), t.nodes.size(), t.local_maps.size(),
                    t.keyframes.size(), double(s.bytes_total) / 1e6);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "ltm_tile_map: %s\n", e.what());
        return 1;
    }
    return 0;
}
