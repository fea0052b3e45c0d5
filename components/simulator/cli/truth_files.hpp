#pragma once
// Ground-truth side files of a simulated run (beside the KITTI-layout scans).
#include <cstdint>
#include <string>
#include <vector>

#include "simulator/core/simulator.hpp"

namespace ltm::sim::cli {

// Identity calibration with P0..P3 and Tr, so KITTI tools read the folder (LiDAR = camera 0).
void write_identity_calib(const std::string& path);
// One line a uint32 label, little-endian (SemanticKITTI layout).
void write_labels(const std::string& path, const std::vector<std::uint32_t>& labels);
// Terrain heights objects.txt gives along each object's long axis (its ends included).
constexpr int kGroundSamples = 5;
// objects.txt: the session's static objects (with the ground under each, kGroundSamples heights
// along its long axis); changes.txt: what differs between sessions;
// actors.txt: the moving actors; kidnaps.txt: output frames that follow an unseen move.
void write_objects(const std::string& path, const Simulator& sim);
void write_changes(const std::string& path, const Simulator& sim);
void write_actors(const std::string& path, const Simulator& sim);
void write_kidnaps(const std::string& path, const std::vector<std::size_t>& frames,
                   const std::vector<double>& stamps);
// The scenario file as given, followed by comment lines with the run's options.
void copy_scenario(const std::string& from, const std::string& to, const std::string& note);

}  // namespace ltm::sim::cli
