#pragma once
// The mapping's saves into its map directory (map_dir): the periodic ones on a thread of their own
// (`mapping/save`), file by file within a CPU budget shared with the other background work
// (common/core/cpu_budget.hpp), and the ones that must be done now (a request, a site's commit,
// the shutdown) on the caller's thread, after the background one under way, which then no longer
// waits for the budget.
//
// Why (issue 28): a save encodes and writes every changed local map, 0.3-0.5 s of CPU on a
// site_loop day in one piece; on the component's thread, beside a maintenance pass and the
// odometry, it made the mission's worst seconds (109 % of a core). Here the pieces are single
// files and the budget decides when the next one starts.
//
// A snapshot shares the mapper's local maps and keyframes (immutable once made), so the thread
// writes a consistent map while the mapper goes on. Saves are numbered: a background save older
// than one already written is skipped, so the directory never goes back to an older map.
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <unordered_map>

#include "common/core/cpu_budget.hpp"
#include "map/core/link_applied.hpp"
#include "map/core/map_data.hpp"
#include "map/core/map_store.hpp"
#include "runtime/worker.hpp"

namespace ltm::mapping {

class MapSaver {
  public:
    // `log(ok, line)` gets each background save's outcome ("map saved to ..." / "map not saved:
    // ..."). budget: nullptr saves at full speed.
    MapSaver(std::string component, std::string dir, map::SaveOptions options,
             std::shared_ptr<common::CpuBudget> budget,
             std::function<void(bool ok, const std::string& line)> log);
    ~MapSaver();

    void start();  // the thread (on_activate)
    // Queues a save of `map`; a save still waiting is replaced (the newest map is what matters).
    void save_in_background(map::MapData map, map::LinkApplied applied);
    // Saves `map` now on this thread, after the background save under way. Throws
    // common::IoError as map::MapWriter::save.
    map::SaveStats save_now(const map::MapData& map, const map::LinkApplied& applied);
    // Finishes what waits without pacing and ends the thread (on_shutdown, before the last save).
    void stop();

    // A background save failed since the last call (the caller saves again at the next period).
    bool take_failed() { return failed_.exchange(false); }
    const std::string& dir() const { return dir_; }
    double background_cpu_s() const { return background_cpu_s_.load(); }
    std::uint64_t background_saves() const { return background_saves_.load(); }
    std::uint64_t skipped() const { return skipped_.load(); }  // older than one written
    double longest_piece_s() const { return longest_piece_s_.load(); }

    // What the newest save written holds of each local map (map::MapWriter::written_local_maps):
    // a local map whose data is still the one written can leave memory (paged out).
    std::unordered_map<std::uint64_t, map::MapWriter::WrittenLocalMap> written_local_maps() const;

    static std::string describe(const std::string& dir, const map::SaveStats& st);

  private:
    struct Job {
        map::MapData map;
        map::LinkApplied applied;
        std::uint64_t seq = 0;
    };
    void work(Job& job, const runtime::StopToken& stop);
    map::SaveStats write(const map::MapData& map, const map::LinkApplied& applied,
                         const std::function<void()>& between);

    std::string dir_;
    map::MapWriter writer_;
    std::shared_ptr<common::CpuBudget> budget_;
    std::function<void(bool, const std::string&)> log_;
    std::mutex writer_mutex_;           // held while the directory is written
    mutable std::mutex written_mutex_;  // guards written_
    std::unordered_map<std::uint64_t, map::MapWriter::WrittenLocalMap> written_;
    std::uint64_t written_seq_ = 0;           // the newest save written (under writer_mutex_)
    std::atomic<std::uint64_t> next_seq_{0};  // numbers the saves as they are asked for
    std::atomic<bool> hurry_{false};          // a save now waits: the background one stops pacing
    std::atomic<bool> failed_{false};
    std::atomic<double> background_cpu_s_{0.0}, longest_piece_s_{0.0};
    std::atomic<std::uint64_t> background_saves_{0}, skipped_{0};
    runtime::Worker<Job> worker_;  // last: stopped before the members it uses go
};

}  // namespace ltm::mapping
