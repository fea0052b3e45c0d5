#pragma once
// What a component's status line says, as data: one code for every state a component reports on
// the shared `status` topic (ltm_msgs/Status `code`, a uint8 with the same values), so that a
// reader switches on it instead of comparing text. to_string() gives the line's text key (the
// Status message's `key`, for people, recorders and logs); parse_status_code() reads it back.
// A new state: one enumerator, one case in to_string() (the compiler asks for it) and the same
// constant in idl/ltm_msgs/msg/Status.idl.
#include <cstdint>
#include <optional>
#include <string>

namespace ltm::common {

enum class StatusCode : std::uint8_t {
    kUnknown = 0,  // a sender that set no code
    // The odometry, about a scan (the line's stamp is the scan's).
    kInitialised = 1,
    kTracked = 2,
    kRecovered = 3,   // registered again after lost or skipped scans (same segment)
    kRestarted = 4,   // a new segment (the line's segment): the odometry frame changed
    kLost = 5,        // no pose for this scan (the localisation: lost on the map)
    kSkipped = 6,     // no pose for this scan: too few points
    kRejected = 7,    // no pose for this scan: its stamp is not after the previous one
    kBadCloud = 8,    // the scan could not be read
    kDegenerate = 9,  // registered, but degenerate in some directions
    // The localisation.
    kRelocalised = 10,
    kOffMap = 11,
    kOnMap = 12,
    kInitialPose = 13,
    kInitialPoseRefused = 14,
    kNoMap = 15,
    kLocalisationFailed = 16,
    // The mapping (and the mesh, for map requests: the line's request_id).
    kNotSolved = 17,
    kSegmentJoined = 18,
    kSegmentNotJoined = 19,
    kSessionJoined = 20,
    kSessionNotJoined = 21,
    kMapRequestDone = 22,
    kMapRequestFailed = 23,
    // The maintenance.
    kMaintained = 24,
    kMaintenanceFailed = 25,
    kWriteFailed = 26,
    // The mesh.
    kBadLocalMap = 27,
    kBadPoseGraph = 28,
    kMeshFailed = 29,
    kMeshUpdated = 30,
    kMeshDepth = 31,
    kMeshWritten = 32,
    kMeshNotWritten = 33,
};
constexpr std::uint8_t kLastStatusCode = 33;

// The text key: "bad_cloud", "restarted", ...
const char* to_string(StatusCode code);
// The code of a text key; nullopt for an unknown one.
std::optional<StatusCode> parse_status_code(const std::string& key);
// The code of a wire value; kUnknown for a value this build does not know (a newer sender).
StatusCode status_code_from_wire(std::uint8_t value);

// The odometry has no pose for the scan the line is about (what the localisation waits for).
bool says_no_pose(StatusCode code);

}  // namespace ltm::common
