#pragma once
// A launch config made into the budget benchmark's: its sensor component replaced by a player of
// a scan folder at the sensor's real rate (so the simulator's rendering is not counted), the
// `points` topic left at its declared (live) role, the sensor presets set to the scans' sensor,
// and the budget probe added.
#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

namespace ltm::bench {

struct VariantOptions {
    std::string replace;       // the component to replace by a kitti_player ("": none)
    std::string scans;         // the KITTI-layout folder it plays
    int wait_for_readers = 1;  // readers of `points` the player waits for before the first scan
    std::string probe_file;    // the probe's CSV ("": no probe)
    std::vector<std::string> probe_inputs;  // points, odometry, pose, map_changes
    std::string probe_pose_topic;           // what the probe's `pose` input reads ("": pose)
    // The sensor preset of the scans played ("": the config's own): set as `preset` of every
    // component that reads one (kPresetTypes), so the config follows the data.
    std::string preset;
};

// The component types whose parameters include a sensor `preset`.
inline constexpr const char* kPresetTypes[] = {"odometry", "localisation", "mapping",
                                               "keyframe_digest"};

// Throws std::runtime_error naming what is wrong (no such component, no components list).
YAML::Node budget_variant(const YAML::Node& config, const VariantOptions& options);
std::vector<std::string> component_names(const YAML::Node& config);

}  // namespace ltm::bench
