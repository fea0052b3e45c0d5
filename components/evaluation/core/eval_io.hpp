#pragma once
// Input files of the evaluation tools (besides trajectories, scans and meshes, read by common).
//
// labels:  NNNNNN.label, one little-endian uint32 a point (see point_labels.hpp).
// loops:   one detected loop a line, `query match [score]` (frame indices; `#` comments).
// reloc:   one attempt a line, `frame time_s ok [r00 r01 r02 tx r10 r11 r12 ty r20 r21 r22 tz]`:
//          ok = 1 with the estimated pose (KITTI 3x4 row-major), ok = 0 without one.
// All readers throw common::IoError naming the file (and line) on bad input.
#include <cstdint>
#include <string>
#include <vector>

#include "evaluation/core/place_recognition.hpp"
#include "evaluation/core/relocalisation.hpp"

namespace ltm::eval {

std::vector<std::uint32_t> read_labels(const std::string& path);
void write_labels(const std::string& path, const std::vector<std::uint32_t>& labels);

std::vector<LoopPair> read_loop_pairs(const std::string& path);
void write_loop_pairs(const std::string& path, const std::vector<LoopPair>& loops);

RelocAttempts read_reloc_attempts(const std::string& path);

}  // namespace ltm::eval
