#pragma once
// What the Mapper (mapper.hpp) answers: the loops it closed and refused, the results of adding a
// keyframe or a local map, and where a session and an odometry segment stand.
#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace ltm::mapping {

struct LoopClosure {
    std::uint32_t query_keyframe = 0, match_keyframe = 0;  // keyframe indices (order of arrival)
    std::uint64_t query_scan = 0, match_scan = 0;          // KeyframeData::scan_index
    std::uint32_t query_session = 0, match_session = 0;
    std::uint32_t query_segment = 0, match_segment = 0;  // odometry segments of the two anchors
    // Same session, across a segment break that no optimised loop had joined yet: verified from
    // the descriptor's guess and accepted on the verification's quality alone.
    bool across_break = false;
    std::uint64_t from_node = 0, to_node = 0;  // the loop edge: match anchor -> query anchor
    Eigen::Isometry3d T_from_to = Eigen::Isometry3d::Identity();
    Eigen::Isometry3d T_match_query = Eigen::Isometry3d::Identity();  // LiDAR to LiDAR
    double descriptor_distance = 0.0;
    double descriptor_yaw = 0.0;  // [rad]
    std::size_t inliers = 0;
    double inlier_fraction = 0.0, inlier_rms = 0.0;
    double correction_translation = 0.0;  // verification result vs the guess it started from [m]
    double disagreement = 0.0;            // with the graph's estimate at the time [m]
    std::size_t structure_points = 0, structure_inliers = 0;  // see registration::LoopVerification
    double min_sector_fraction = 1.0;                         // see registration::LoopVerification
    bool from_graph_guess = false;  // verified from the graph's estimate, not the descriptor's
    // Between places already joined by loops, agreeing with the graph to within
    // long_term.agree_translation / agree_rotation: added without making an optimisation due.
    bool agrees = false;
    EIGEN_MAKE_ALIGNED_OPERATOR_NEW
};

struct LoopRejection {
    std::uint32_t match_keyframe = 0;
    double descriptor_distance = 0.0;
    std::string reason;
};

struct KeyframeResult {
    bool added = false;
    std::string message;  // why it was not added (one line)
    // Stored (a new keyframe index). False: at a mapped place, within long_term.keyframe_distance
    // and keyframe_angle of stored keyframe `index`, which stands for it (its loops name it).
    bool kept = false;
    std::uint32_t index = 0;              // keyframe index when added
    std::size_t candidates = 0;           // descriptor candidates under the threshold
    bool verified = false;                // candidates were verified (not in the cool-down)
    std::vector<LoopClosure> loops;       // accepted: their edges are in the graph
    std::vector<LoopRejection> rejected;  // refused by the verification
    // A loop that does not merely agree with the graph.
    bool optimisation_due() const {
        for (const LoopClosure& l : loops) {
            if (!l.agrees) return true;
        }
        return false;
    }
};

// A localisation fix of a keyframe (Mapper::add_map_fix).
struct MapFixResult {
    bool added = false;
    std::string message;            // why not, or what it did (one line)
    bool placed_part = false;       // the first fix of its part: the part was set where it says
    bool optimisation_due = false;  // it does not merely agree with the graph
    double disagreement = 0.0;      // with the graph's estimate before it [m]
    std::uint64_t from_node = 0, to_node = 0;  // the edge: loaded map node -> keyframe's node
};

struct LocalMapResult {
    bool added = false;   // stored (new, or a newer snapshot of a known map)
    std::string message;  // why not (one line)
    std::uint64_t node = 0;
    // Folded into the existing local map of graph node `node` (an earlier lap's or session's).
    bool merged = false;
};

// A session of the Mapper (robot), placed on the map by loops or not.
struct SessionStatus {
    std::uint32_t session = 0;
    std::string robot;  // "" for the default session unless it was opened for a robot
    // Placed with the map's first session by loops (as of the last optimisation); the map's first
    // session always.
    bool joined = false;
    std::uint32_t joined_at_keyframe = 0;  // query keyframe of the earliest loop joining it
    // "session 1 (robot2) joined to the map by a loop at keyframe 40", or what its poses are.
    std::string message;
};

// An odometry segment of the current session.
struct SegmentStatus {
    std::uint32_t segment = 0;
    std::uint64_t first_local_map = 0;  // the odometry's id of its first local map known here
    // Placed by loops as of the last optimisation (segment 0 always): by a chain of active loop
    // edges to segment 0 or to an earlier session's map.
    bool joined = false;
    std::uint32_t joined_at_keyframe = 0;  // query keyframe of the earliest loop joining it
    // "segment 1 joined to the map by a loop at keyframe 40", or what its poses are until then.
    std::string message;
};

}  // namespace ltm::mapping
