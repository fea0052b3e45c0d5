#include "mapping/component/map_edit_inputs.hpp"

#include <utility>

#include "mapping/component/map_change_cells.hpp"
#include "runtime/convert/geometry.hpp"

namespace ltm::mapping {

using runtime::TopicRole;

MapEditInputs::MapEditInputs(runtime::ComponentContext& ctx, Mapper& mapper, std::uint32_t session,
                             const Options& options, std::function<void(const std::string&)> placed,
                             std::function<void()> optimise)
    : ctx_(ctx),
      mapper_(mapper),
      session_(session),
      options_(options),
      placed_(std::move(placed)),
      optimise_(std::move(optimise)),
      pairer_(options.fix_after) {
    mapper_.expect_map_fixes(options_.use_fixes);
    if (options_.subscribe_fixes) {  // the topics exist on a new site too; unused there
        ctx.subscribe<msg::LocalisationStatus>(
            "localisation_status", TopicRole::kState, [this](const msg::LocalisationStatus& m) {
                if (!options_.use_fixes) return;
                apply(pairer_.state(convert::to_seconds(m.header.stamp),
                                    m.state == ltm_msgs_msg_LocalisationStatus_Constants_TRACKING));
            });
        ctx.subscribe<msg::PoseWithCovarianceStamped>(
            "localisation_pose", TopicRole::kState,
            [this](const msg::PoseWithCovarianceStamped& m) {
                if (!options_.use_fixes) return;
                apply(pairer_.pose(convert::to_seconds(m.header.stamp),
                                   convert::to_isometry(m.pose.pose)));
            });
    }
    if (options_.apply_changes)
        for (std::size_t i = 0; i < options_.change_topics.size(); ++i)
            ctx.subscribe<msg::MapChangeSet>(options_.change_topics[i], TopicRole::kMap,
                                             [this, i](const msg::MapChangeSet& m) {
                                                 on_changes(m);
                                                 if (taken_) taken_(i);
                                             });
}

void MapEditInputs::keyframe(const common::KeyframeData& keyframe, std::uint32_t index) {
    if (!options_.use_fixes) return;
    apply(
        pairer_.keyframe(keyframe.stamp, {keyframe.local_map_id, keyframe.T_anchor_lidar, index}));
}

void MapEditInputs::apply(const std::optional<PairedFix>& f) {
    if (!f) return;
    const MapFixResult r =
        mapper_.add_map_fix(session_, f->keyframe.local_map_id, f->keyframe.T_anchor_lidar,
                            f->T_world_lidar, f->keyframe.index);
    if (!r.added) {
        if (r.message.rfind("fix refused", 0) == 0) {
            ++refused_;
            ctx_.log().debug(r.message);
        }
        return;
    }
    if (r.placed_part) placed_("placed on the loaded map by the localisation: " + r.message);
    if (r.optimisation_due) optimise_();
}

// What map maintenance removed leaves the local maps (localisation and loop verification use
// them, and tomorrow's map is saved from them); new objects found there stay.
void MapEditInputs::on_changes(const msg::MapChangeSet& m) {
    const ChangeCells c = change_cells(m);
    if (!c.frame_id.empty() && c.frame_id != options_.frame_id) {
        if (!warned_frame_)
            ctx_.log().warn("map_changes in frame '" + c.frame_id + "', not the map's '" +
                            options_.frame_id + "': left out");
        warned_frame_ = true;
        return;
    }
    if (c.malformed > 0)
        ctx_.log().warn(std::to_string(c.malformed) + " malformed change(s) in map_changes pass " +
                        std::to_string(m.pass) + ": left out");
    mapper_.keep_cells(c.added, c.cell_size);
    if (c.removed.empty()) return;
    const std::size_t cleared = mapper_.remove_cells(c.removed, c.cell_size);
    ctx_.log().info("map maintenance pass " + std::to_string(m.pass) + ": " +
                    std::to_string(c.removed_segments) + " segment(s) gone, " +
                    std::to_string(cleared) + " voxels cleared from the local maps");
}

std::string MapEditInputs::summary() const {
    std::string out;
    if (options_.use_fixes)
        out = std::to_string(mapper_.map_fixes()) +
              " keyframes tied to the loaded map by the localisation (" + std::to_string(refused_) +
              " fixes refused)";
    if (mapper_.removed_voxels() > 0)
        out += (out.empty() ? "" : "; ") + std::to_string(mapper_.removed_voxels()) +
               " voxels cleared from the local maps by map maintenance";
    return out;
}

}  // namespace ltm::mapping
