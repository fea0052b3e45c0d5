#include "evaluation/cli/run_folder.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/core/io_error.hpp"
#include "recorder/core/mcap_reader.hpp"

namespace ltm::eval::cli {

namespace fs = std::filesystem;

namespace {

constexpr std::size_t kMaxFiles = 400;
constexpr std::size_t kMaxProblemLines = 40;
constexpr std::size_t kMaxFigures = 16;

bool ends_with(const std::string& s, const std::string& tail) {
    return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

// Strips the terminal's colour escapes the launcher writes into host.log.
std::string plain(const std::string& line) {
    std::string out;
    for (std::size_t i = 0; i < line.size(); ++i) {
        if (line[i] == '\033') {
            while (i < line.size() && line[i] != 'm') ++i;
            continue;
        }
        out += line[i];
    }
    return out;
}

void read_host_log(RunFolder& run) {
    std::ifstream in(run.host_log);
    std::string line;
    while (std::getline(in, line)) {
        line = plain(line);
        if (run.launch_line.empty() && line.find("running ") != std::string::npos &&
            line.find(".yaml") != std::string::npos) {
            run.launch_line = line.substr(line.find("running "));
        }
        if (line.find("[host] running ") != std::string::npos) {
            run.components_line = line.substr(line.find("running "));
        }
        const bool warning = line.find(" warn ") != std::string::npos;
        const bool error = line.find(" error ") != std::string::npos;
        run.warnings += warning;
        run.errors += error;
        if ((warning || error) && run.problem_lines.size() < kMaxProblemLines) {
            run.problem_lines.push_back(line);
        }
    }
}

void read_status(RunFolder& run, const std::string& mcap) {
    try {
        recorder::McapReader reader(mcap);
        std::vector<std::string> topics;
        for (const auto& [id, channel] : reader.channels()) {
            const auto schema = reader.schemas().find(channel.schema_id);
            if (schema != reader.schemas().end() &&
                schema->second.name.find("LocalisationStatus") != std::string::npos) {
                topics.push_back(channel.topic);
            }
        }
        for (const std::string& topic : topics) {
            StatusStream stream;
            stream.file = mcap;
            stream.topic = topic;
            recorder::ReadOptions options;
            options.topics = {topic};
            recorder::MessageCursor cursor = reader.messages(options);
            std::size_t bad = 0;
            std::string first_error;
            for (recorder::MessageView m; cursor.next(m);) {
                StatusSample s;
                std::string error;
                if (decode_localisation_status(m.data, m.size, &s, &error)) {
                    stream.samples.push_back(std::move(s));
                } else if (bad++ == 0) {
                    first_error = error;
                }
            }
            if (bad > 0)
                stream.problem = std::to_string(bad) + " messages not decoded: " + first_error;
            if (!reader.problem().empty()) {
                stream.problem += (stream.problem.empty() ? "" : "; ") + reader.problem();
            }
            run.status_streams.push_back(std::move(stream));
        }
    } catch (const common::IoError& e) {
        StatusStream stream;
        stream.file = mcap;
        stream.topic = "(unreadable)";
        stream.problem = e.what();
        run.status_streams.push_back(std::move(stream));
    }
}

void summarise_changes(RunFolder& run, const std::string& path) {
    std::ifstream in(path);
    std::string line;
    std::size_t passes = 0;
    long moving = 0, vanished = 0, added = 0, removed = 0;
    while (std::getline(in, line)) {
        // "session S pass P at T s: M moving, V vanished, A new segments; R of N voxels removed,
        // ..."
        if (line.rfind("session ", 0) != 0 || line.find(" pass ") == std::string::npos) continue;
        std::istringstream s(line.substr(line.find(':') + 1));
        long m = 0, v = 0, a = 0, r = 0;
        std::string w;
        if (s >> m >> w >> v >> w >> a >> w >> w >> r) {
            ++passes;
            moving += m;
            vanished += v;
            added += a;
            removed += r;
        }
    }
    if (passes == 0) return;
    run.maintenance_summary = fs::relative(path, run.dir).string() + ": " + std::to_string(passes) +
                              " passes; " + std::to_string(moving) + " moving, " +
                              std::to_string(vanished) + " vanished, " + std::to_string(added) +
                              " new segments; " + std::to_string(removed) + " voxels removed";
    run.text_reports.push_back(path);
}

}  // namespace

RunFolder scan_run_folder(const std::string& dir) {
    RunFolder run;
    run.dir = fs::path(dir).lexically_normal().string();
    std::error_code ec;
    fs::recursive_directory_iterator it(dir, fs::directory_options::skip_permission_denied, ec);
    if (ec) throw common::IoError(dir, "cannot list: " + ec.message());
    std::vector<fs::path> paths;
    for (const fs::recursive_directory_iterator end; it != end; it.increment(ec)) {
        if (ec) break;
        if (it.depth() >= 3) it.disable_recursion_pending();
        if (it->is_regular_file(ec)) paths.push_back(it->path());
    }
    std::sort(paths.begin(), paths.end());
    for (const fs::path& p : paths) {
        const std::string rel = fs::relative(p, dir, ec).string();
        const std::string name = p.filename().string();
        const bool top = p.parent_path() == fs::path(dir) || rel.find('/') == std::string::npos;
        if (run.files.size() < kMaxFiles) run.files.emplace_back(rel, fs::file_size(p, ec));
        if (name == "report.html") continue;
        if (top && name == "host.log") run.host_log = p.string();
        if (top && name == "launch.yaml") run.launch_copy = p.string();
        if (top && name == "run.txt") {
            std::ifstream in(p);
            for (std::string line; std::getline(in, line);) {
                const std::size_t colon = line.find(": ");
                if (colon != std::string::npos) {
                    run.run_record.emplace_back(line.substr(0, colon), line.substr(colon + 2));
                }
            }
        }
        if (top && name == "exit_status") {
            std::ifstream in(p);
            std::getline(in, run.exit_status);
        }
        if (top && name == "ground_truth_tum.txt") {
            run.reference = p.string();
        } else if (top && ends_with(name, "_tum.txt")) {
            run.trajectories.emplace_back(name.substr(0, name.size() - 8), p.string());
        }
        // Figures at the top or one folder down (a benchmark's score/), but not the evaluations'
        // (eval_*/: the trajectories section draws those).
        const std::size_t slashes =
            static_cast<std::size_t>(std::count(rel.begin(), rel.end(), '/'));
        if (ends_with(name, ".svg") && slashes <= 1 && rel.rfind("eval_", 0) != 0 &&
            run.figures.size() < kMaxFigures && fs::file_size(p, ec) < (std::uintmax_t{4} << 20)) {
            run.figures.push_back(p.string());
        }
        if (top && name == "global_map.ply") run.map_clouds.push_back(p.string());
        // This run's changes (its folder or maintenance/), not a nested run's (another_day/...).
        if (name == "changes_removed_added.ply" && std::count(rel.begin(), rel.end(), '/') <= 1) {
            run.change_clouds.push_back(p.string());
        }
        if (ends_with(name, ".mcap") && rel.find('/') == std::string::npos)
            read_status(run, p.string());
        if (name == "changes.txt" && run.maintenance_summary.empty())
            summarise_changes(run, p.string());
        if ((name.rfind("eval_", 0) == 0 && ends_with(name, ".txt")) || name == "metrics.txt") {
            run.text_reports.push_back(p.string());
        }
    }
    if (!run.host_log.empty()) read_host_log(run);
    return run;
}

}  // namespace ltm::eval::cli
