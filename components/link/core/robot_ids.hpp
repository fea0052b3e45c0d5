#pragma once
// A robot's numbers across its restarts. The odometry numbers keyframes, local maps and odometry
// segments from 0 at every start, while the base station's mapping keeps one session a robot, in
// which a number means one keyframe, one local map, one segment. So the robot's uplink renumbers
// what it stores: each run (start) of the robot continues after the largest numbers any earlier
// run stored, kept in a small file beside the backlog (`<backlog_dir>/ids`), and a restarted
// robot's segment 0 becomes a new segment: the mapping takes the restart as an odometry break
// (no odometry relation to the maps before; loops join it to the map, as after a lost track).
// The robot's first run changes nothing (its messages go out byte for byte).
#include <cstdint>
#include <string>
#include <vector>

namespace ltm::link {

// Next free numbers (or what is added to a run's own numbers).
struct RobotIds {
    std::uint64_t keyframe = 0;
    std::uint64_t local_map = 0;
    std::uint32_t segment = 0;
    bool operator==(const RobotIds& o) const {
        return keyframe == o.keyframe && local_map == o.local_map && segment == o.segment;
    }
};

class RobotIdRenumbering {
  public:
    // Reads `file`: absent, the robot's first run (offsets 0). Throws common::IoError (one line:
    // the file, what is wrong) when it cannot be read or is damaged.
    explicit RobotIdRenumbering(std::string file);

    // Added to this run's numbers.
    const RobotIds& offsets() const { return offsets_; }
    // Next free numbers after everything renumbered so far (what the file will say).
    const RobotIds& next() const { return next_; }

    // Renumbers a ltm_msgs Keyframe_ or LocalMap_ in its CDR (in place) and takes its numbers
    // into next(); other types are left alone. False, and left alone, when it does not parse.
    bool renumber(const std::string& dds_type, std::vector<std::uint8_t>& cdr);

    // Writes next() when it changed since the last save, atomically (a temporary file renamed).
    // Throws common::IoError when the disk refuses.
    void save();

  private:
    std::string file_;
    RobotIds offsets_, next_, saved_;
};

}  // namespace ltm::link
