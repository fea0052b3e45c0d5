#pragma once
// What the mapping learns from the rest of the robot, beside its odometry and loops (issue 26):
// the localisation's tracked poses of its keyframes, which tie a session continuing a loaded map to
// it (Mapper::add_map_fix, paired by MapFixPairer), and map maintenance's changes, whose removed
// segments leave the local maps (Mapper::remove_cells / keep_cells). Subscribes
// `localisation_status` and `localisation_pose` (when asked for: one robot), `map_changes` (when
// asked for); the component hands it each keyframe it added.
// A pass's removed cells are cleared from the local maps one local map at a time on a timer of the
// component's thread, their CPU kept to `clear_share` of one core (common/core/cpu_pacer.hpp): a
// pass that clears a site's worth of local maps (0.3-0.5 s of CPU at once before, beside the
// maintenance worker's own pass: the robot's worst seconds, issue 28) is spread over a few
// seconds, and the thread takes its other inputs between two local maps. Before a save and at the
// end everything waiting is cleared at once (a saved map never lacks an edit it acknowledged).
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/core/cpu_pacer.hpp"
#include "common/core/local_map_data.hpp"
#include "mapping/core/map_fix_pairer.hpp"
#include "mapping/core/mapper.hpp"
#include "runtime/component.hpp"

namespace ltm::mapping {

class MapEditInputs {
  public:
    struct Options {
        bool subscribe_fixes = false;  // the localisation's topics exist (remappable)
        bool use_fixes = false;        // and a loaded map to tie to
        int fix_after = 3;             // scans tracked in a row
        bool apply_changes = true;
        // Where maintenance's changes come from: one robot's relative `map_changes`, or each
        // robot's /R/map_changes at a base station (the robot's maintenance, over its uplink).
        std::vector<std::string> change_topics = {"map_changes"};
        std::string frame_id = "map";
        // Clearing a pass's cells: at most this share of one core (1: all at once, on arrival).
        double clear_share = 0.15;
        // Or drawing from this budget, shared with the process's other background work
        // (common/core/cpu_budget.hpp; its share is clear_share).
        std::shared_ptr<common::CpuBudget> budget;
    };
    // `placed` is told when a fix placed a part on the loaded map; `optimise` when one made an
    // optimisation due.
    MapEditInputs(runtime::ComponentContext& ctx, Mapper& mapper, std::uint32_t session,
                  const Options& options, std::function<void(const std::string&)> placed,
                  std::function<void()> optimise);

    // A keyframe the mapper added (its index).
    void keyframe(const common::KeyframeData& keyframe, std::uint32_t index);
    // One line for the log at the end ("" when there is nothing to say).
    std::string summary() const;
    // Told, after each MapChangeSet taken, which of change_topics it came on (its index): the
    // link's packets the mapping holds (map/core/link_applied.hpp).
    void on_taken(std::function<void(std::size_t)> taken) { taken_ = std::move(taken); }
    // Clears every local map still waiting for a pass's cells now (before a save, at the end).
    void finish_clearing();

  private:
    void apply(const std::optional<PairedFix>& fix);
    void on_changes(const msg::MapChangeSet& m);
    // The timer: clears waiting local maps while the pacer allows (clear_share).
    void clear_some();
    void clearing_done();

    runtime::ComponentContext& ctx_;
    Mapper& mapper_;
    std::uint32_t session_;
    Options options_;
    std::function<void(const std::string&)> placed_;
    std::function<void()> optimise_;
    std::function<void(std::size_t)> taken_;
    MapFixPairer pairer_;
    std::size_t refused_ = 0;
    bool warned_frame_ = false;
    // The clearing under way: the passes it holds, their segments, voxels cleared, when it began,
    // its CPU so far [s].
    struct Clearing {
        std::string passes;
        std::size_t segments = 0, voxels = 0;
        double started_s = 0.0, cpu_s = 0.0;
    };
    std::optional<Clearing> clearing_;
    std::optional<common::CpuPacer> pacer_;  // clear_share < 1, or a shared budget
    double clear_cpu_s_ = 0.0;               // CPU spent clearing so far (the pacer's clock)
    double resume_at_s_ = 0.0;               // wall clock: the pacer's wait ends
};

}  // namespace ltm::mapping
