#include "common/core/status_code.hpp"

namespace ltm::common {

const char* to_string(StatusCode code) {
    switch (code) {
        case StatusCode::kUnknown:
            return "unknown";
        case StatusCode::kInitialised:
            return "initialised";
        case StatusCode::kTracked:
            return "tracked";
        case StatusCode::kRecovered:
            return "recovered";
        case StatusCode::kRestarted:
            return "restarted";
        case StatusCode::kLost:
            return "lost";
        case StatusCode::kSkipped:
            return "skipped";
        case StatusCode::kRejected:
            return "rejected";
        case StatusCode::kBadCloud:
            return "bad_cloud";
        case StatusCode::kDegenerate:
            return "degenerate";
        case StatusCode::kRelocalised:
            return "relocalised";
        case StatusCode::kOffMap:
            return "off_map";
        case StatusCode::kOnMap:
            return "on_map";
        case StatusCode::kInitialPose:
            return "initialpose";
        case StatusCode::kInitialPoseRefused:
            return "initialpose_refused";
        case StatusCode::kNoMap:
            return "no_map";
        case StatusCode::kLocalisationFailed:
            return "localisation_failed";
        case StatusCode::kNotSolved:
            return "not_solved";
        case StatusCode::kSegmentJoined:
            return "segment_joined";
        case StatusCode::kSegmentNotJoined:
            return "segment_not_joined";
        case StatusCode::kSessionJoined:
            return "session_joined";
        case StatusCode::kSessionNotJoined:
            return "session_not_joined";
        case StatusCode::kMapRequestDone:
            return "map_request_done";
        case StatusCode::kMapRequestFailed:
            return "map_request_failed";
        case StatusCode::kMaintained:
            return "maintained";
        case StatusCode::kMaintenanceFailed:
            return "maintenance_failed";
        case StatusCode::kWriteFailed:
            return "write_failed";
        case StatusCode::kBadLocalMap:
            return "bad_local_map";
        case StatusCode::kBadPoseGraph:
            return "bad_pose_graph";
        case StatusCode::kMeshFailed:
            return "mesh_failed";
        case StatusCode::kMeshUpdated:
            return "mesh_updated";
        case StatusCode::kMeshDepth:
            return "mesh_depth";
        case StatusCode::kMeshWritten:
            return "mesh_written";
        case StatusCode::kMeshNotWritten:
            return "mesh_not_written";
    }
    return "unknown";  // a value outside the enum (not reachable through status_code_from_wire)
}

StatusCode status_code_from_wire(std::uint8_t value) {
    return value <= kLastStatusCode ? static_cast<StatusCode>(value) : StatusCode::kUnknown;
}

std::optional<StatusCode> parse_status_code(const std::string& key) {
    for (std::uint8_t v = 0; v <= kLastStatusCode; ++v) {
        const StatusCode c = static_cast<StatusCode>(v);
        if (key == to_string(c)) return c;
    }
    return std::nullopt;
}

bool says_no_pose(StatusCode code) {
    switch (code) {
        case StatusCode::kLost:
        case StatusCode::kSkipped:
        case StatusCode::kRejected:
        case StatusCode::kBadCloud:
            return true;
        case StatusCode::kUnknown:
        case StatusCode::kInitialised:
        case StatusCode::kTracked:
        case StatusCode::kRecovered:
        case StatusCode::kRestarted:
        case StatusCode::kDegenerate:
        case StatusCode::kRelocalised:
        case StatusCode::kOffMap:
        case StatusCode::kOnMap:
        case StatusCode::kInitialPose:
        case StatusCode::kInitialPoseRefused:
        case StatusCode::kNoMap:
        case StatusCode::kLocalisationFailed:
        case StatusCode::kNotSolved:
        case StatusCode::kSegmentJoined:
        case StatusCode::kSegmentNotJoined:
        case StatusCode::kSessionJoined:
        case StatusCode::kSessionNotJoined:
        case StatusCode::kMapRequestDone:
        case StatusCode::kMapRequestFailed:
        case StatusCode::kMaintained:
        case StatusCode::kMaintenanceFailed:
        case StatusCode::kWriteFailed:
        case StatusCode::kBadLocalMap:
        case StatusCode::kBadPoseGraph:
        case StatusCode::kMeshFailed:
        case StatusCode::kMeshUpdated:
        case StatusCode::kMeshDepth:
        case StatusCode::kMeshWritten:
        case StatusCode::kMeshNotWritten:
            return false;
    }
    return false;
}

}  // namespace ltm::common
