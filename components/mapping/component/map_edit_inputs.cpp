#include "mapping/component/map_edit_inputs.hpp"

#include <cstdio>
#include <utility>

#include "common/core/thread_clock.hpp"
#include "mapping/component/map_change_cells.hpp"
#include "runtime/convert/geometry.hpp"

namespace ltm::mapping {
namespace {

constexpr double kClearTick = 0.05;   // [s] the clearing timer's period
constexpr double kClearBurst = 0.05;  // [s] of CPU the clearing may use at once

}  // namespace

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
    if (options_.apply_changes && (options_.clear_share < 1.0 || options_.budget)) {
        if (options_.budget) {
            pacer_.emplace(options_.budget);
        } else {
            pacer_.emplace(options_.clear_share, kClearBurst);
        }
        pacer_->wait_after(0.0, common::steady_wall_s());  // starts its clocks
        ctx.add_timer(kClearTick, [this] { clear_some(); });
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
    if (!pacer_) {  // all at once
        const double cpu0 = common::thread_cpu_s();
        const std::size_t cleared = mapper_.remove_cells(c.removed, c.cell_size, c.vanished);
        char cpu[64];
        std::snprintf(cpu, sizeof cpu, " (%.2f s of CPU at once)", common::thread_cpu_s() - cpu0);
        ctx_.log().info("map maintenance pass " + std::to_string(m.pass) + ": " +
                        std::to_string(c.removed_segments) + " segment(s) gone, " +
                        std::to_string(cleared) + " voxels cleared from the local maps" + cpu);
        return;
    }
    // Recorded now (local maps that arrive are cleared of the cells at once); the local maps
    // present are cleared by the timer, a few at a time.
    if (!clearing_) clearing_.emplace(Clearing{"", 0, 0, common::steady_wall_s()});
    clearing_->passes += (clearing_->passes.empty() ? "" : ", ") + std::to_string(m.pass);
    clearing_->segments += c.removed_segments;
    if (mapper_.remove_cells_in_steps(c.removed, c.cell_size, c.vanished) == 0) clearing_done();
}

void MapEditInputs::clear_some() {
    if (!clearing_) return;
    const double now = common::steady_wall_s();
    if (now < resume_at_s_) return;
    // A shared budget may be in debt from the others' work: wait for it before a piece.
    if (const double wait = pacer_->wait_now(now); wait > 1e-6) {
        resume_at_s_ = now + wait;
        return;
    }
    for (;;) {
        const double cpu0 = common::thread_cpu_s();
        std::size_t removed = 0;
        const bool more = mapper_.clear_removed_step(&removed);
        const double cpu = common::thread_cpu_s() - cpu0;
        clear_cpu_s_ += cpu;
        clearing_->cpu_s += cpu;
        clearing_->voxels += removed;
        if (!more) {
            clearing_done();
            break;
        }
        const double wait = pacer_->wait_after(clear_cpu_s_, common::steady_wall_s());
        if (wait > 0.0) {
            resume_at_s_ = common::steady_wall_s() + wait;
            break;
        }
    }
}

void MapEditInputs::finish_clearing() {
    if (!clearing_) return;
    std::size_t removed = 0;
    const double cpu0 = common::thread_cpu_s();
    for (bool more = true; more;) {
        more = mapper_.clear_removed_step(&removed);
        clearing_->voxels += removed;
    }
    clearing_->cpu_s += common::thread_cpu_s() - cpu0;
    clearing_done();
}

void MapEditInputs::clearing_done() {
    if (!clearing_) return;
    char took[96];
    std::snprintf(took, sizeof took, " (%.2f s of CPU over %.1f s)", clearing_->cpu_s,
                  common::steady_wall_s() - clearing_->started_s);
    const bool several = clearing_->passes.find(',') != std::string::npos;
    ctx_.log().info("map maintenance pass" + std::string(several ? "es " : " ") +
                    clearing_->passes + ": " + std::to_string(clearing_->segments) +
                    " segment(s) gone, " + std::to_string(clearing_->voxels) +
                    " voxels cleared from the local maps" + took);
    clearing_.reset();
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
