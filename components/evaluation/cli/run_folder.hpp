#pragma once
// What a run folder holds, for the run report: the host's log, the trajectories, the map and
// change clouds, the localisation status recorded in MCAP files, the text reports and every file.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "evaluation/core/localisation_timeline.hpp"

namespace ltm::eval::cli {

struct StatusStream {
    std::string file, topic, problem;  // problem: the recording's damage or undecodable messages
    std::vector<StatusSample> samples;
};

struct RunFolder {
    std::string dir;
    std::vector<std::pair<std::string, std::string>> run_record;  // run.txt's "key: value" lines
    std::string launch_copy;                   // launch.yaml (the launcher's copy), or empty
    std::string host_log;                      // path, or empty
    std::string launch_line, components_line;  // the host's "running ..." lines
    std::string exit_status;
    std::size_t warnings = 0, errors = 0;
    std::vector<std::string> problem_lines;  // the first warning and error lines
    std::string reference;                   // ground_truth_tum.txt, or empty
    std::vector<std::pair<std::string, std::string>> trajectories;  // name, *_tum.txt path
    std::vector<std::string> map_clouds, change_clouds;             // PLY files
    std::vector<StatusStream> status_streams;
    std::string maintenance_summary;        // totals of maintenance/changes.txt
    std::vector<std::string> text_reports;  // eval_*.txt, metrics.txt, ...
    std::vector<std::string> figures;       // SVG files at the top or one folder down, not eval_*/
    std::vector<std::pair<std::string, std::uintmax_t>> files;  // relative path, size
};

// Looks through `dir` (and its sub-folders, 3 levels deep). Throws common::IoError only when
// `dir` cannot be listed; unreadable parts are left out or described.
RunFolder scan_run_folder(const std::string& dir);

}  // namespace ltm::eval::cli
