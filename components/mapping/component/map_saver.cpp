#include "mapping/component/map_saver.hpp"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <optional>
#include <thread>

#include "common/core/cpu_pacer.hpp"
#include "common/core/io_error.hpp"
#include "common/core/thread_clock.hpp"

namespace ltm::mapping {

namespace {
constexpr double kPaceSlice = 0.05;  // [s] a wait is cut into (a hurry or a stop ends it)
}

MapSaver::MapSaver(std::string component, std::string dir, map::SaveOptions options,
                   std::shared_ptr<common::CpuBudget> budget,
                   std::function<void(bool ok, const std::string& line)> log)
    : dir_(std::move(dir)),
      writer_(dir_, std::move(options)),
      budget_(std::move(budget)),
      log_(std::move(log)),
      worker_(
          {std::move(component), "save", 1, runtime::BusyPolicy::kDropOldest,
           runtime::StopPolicy::kFinish},
          [this](runtime::Worker<Job>::Step& step, const runtime::StopToken& stop) {
              if (step.item) work(*step.item, stop);
          },
          [this](const std::string& what) {
              failed_ = true;
              log_(false, "map not saved: " + what);
          }) {}

MapSaver::~MapSaver() { stop(); }

void MapSaver::start() { worker_.start(); }

void MapSaver::stop() {
    hurry_ = true;
    worker_.stop();
}

std::unordered_map<std::uint64_t, map::MapWriter::WrittenLocalMap> MapSaver::written_local_maps()
    const {
    std::unordered_map<std::uint64_t, map::MapWriter::WrittenLocalMap> out;
    {
        std::lock_guard<std::mutex> lock(written_mutex_);
        out = written_;
    }
    // Only files still there as written: a map paged out on a file that is gone would be lost
    // (a lifelong session's site component, constructed after the mapping, removed the staging
    // the mapping's first save had just filled; site_week lost a day's version so. The staging
    // is now the session's own, map/core/site_staging.hpp: this guards against any other loss of
    // a file). The next save writes the others again (MapWriter checks its files' sizes).
    std::error_code ec;
    for (auto it = out.begin(); it != out.end();) {
        const map::LocalMapFile* f = it->second.file.get();
        const bool there =
            f && std::filesystem::file_size(std::filesystem::path(dir_) / f->file, ec) == f->size &&
            !ec;
        it = there ? std::next(it) : out.erase(it);
    }
    return out;
}

std::string MapSaver::describe(const std::string& dir, const map::SaveStats& st) {
    return "map saved to " + dir + " (" + std::to_string(st.files_written) + " files written, " +
           std::to_string(st.bytes_total >> 20) + " MiB in all)";
}

void MapSaver::save_in_background(map::MapData map, map::LinkApplied applied) {
    worker_.push(Job{std::move(map), std::move(applied), ++next_seq_});
}

map::SaveStats MapSaver::save_now(const map::MapData& map, const map::LinkApplied& applied) {
    const std::uint64_t seq = ++next_seq_;
    hurry_ = true;
    std::lock_guard<std::mutex> lock(writer_mutex_);
    hurry_ = false;
    map::SaveStats st = write(map, applied, {});
    written_seq_ = std::max(written_seq_, seq);
    return st;
}

map::SaveStats MapSaver::write(const map::MapData& map, const map::LinkApplied& applied,
                               const std::function<void()>& between) {
    const map::SaveStats st = writer_.save(map, between);
    {
        std::lock_guard<std::mutex> lock(written_mutex_);
        written_ = writer_.written_local_maps();
    }
    // After the manifest: a version committed from this save holds both (the site component
    // commits only once a save is done), so its record is never ahead of it.
    if (!applied.empty()) map::save_link_applied(dir_, applied);
    return st;
}

void MapSaver::work(Job& job, const runtime::StopToken& stop) {
    std::lock_guard<std::mutex> lock(writer_mutex_);
    if (job.seq <= written_seq_) {  // a save now came after it: the directory is newer
        ++skipped_;
        return;
    }
    const double cpu0 = common::thread_cpu_s();
    std::optional<common::CpuPacer> pacer;
    if (budget_) {
        pacer.emplace(budget_);
        pacer->wait_after(cpu0, common::steady_wall_s());  // starts its clocks
    }
    // Between two files: the budget's wait, cut short by a save that must be done now or a stop.
    double piece_start = cpu0;
    auto between = [&] {
        const double cpu = common::thread_cpu_s();
        double longest = longest_piece_s_.load();
        while (cpu - piece_start > longest &&
               !longest_piece_s_.compare_exchange_weak(longest, cpu - piece_start)) {
        }
        if (pacer) {
            double wait = pacer->wait_after(cpu, common::steady_wall_s());
            while (wait > 0.0 && !hurry_ && !stop.stop_requested()) {
                const double slice = std::min(wait, kPaceSlice);
                std::this_thread::sleep_for(std::chrono::duration<double>(slice));
                wait -= slice;
            }
            pacer->waited(common::steady_wall_s());
        }
        piece_start = common::thread_cpu_s();
    };
    try {
        const map::SaveStats st = write(job.map, job.applied, between);
        between();  // the manifest's piece is charged too
        written_seq_ = job.seq;
        ++background_saves_;
        log_(true, describe(dir_, st));
    } catch (const common::IoError& e) {
        failed_ = true;
        log_(false, std::string("map not saved: ") + e.what());
    }
    double total = background_cpu_s_.load();
    const double used = common::thread_cpu_s() - cpu0;
    while (!background_cpu_s_.compare_exchange_weak(total, total + used)) {
    }
}

}  // namespace ltm::mapping
