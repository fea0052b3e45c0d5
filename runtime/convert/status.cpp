#include "runtime/convert/status.hpp"

#include "runtime/convert/dds_string.hpp"

namespace ltm::convert {

// The wire constants are the enum's values.
static_assert(ltm_msgs_msg_Status_Constants_CODE_UNKNOWN ==
              std::uint8_t(common::StatusCode::kUnknown));
static_assert(ltm_msgs_msg_Status_Constants_CODE_RESTARTED ==
              std::uint8_t(common::StatusCode::kRestarted));
static_assert(ltm_msgs_msg_Status_Constants_CODE_MAP_REQUEST_FAILED ==
              std::uint8_t(common::StatusCode::kMapRequestFailed));
static_assert(ltm_msgs_msg_Status_Constants_CODE_MESH_NOT_WRITTEN == common::kLastStatusCode);

Owned<msg::Status> to_msg(const StatusData& s) {
    Owned<msg::Status> m;
    m->header.stamp = s.stamp;
    set_string(m->header.frame_id, s.frame_id);
    set_string(m->component, s.component);
    m->level = static_cast<std::uint8_t>(s.level);
    m->code = static_cast<std::uint8_t>(s.code);
    set_string(m->key, common::to_string(s.code));
    set_string(m->message, s.message);
    m->segment = s.segment;
    m->request_id = s.request_id;
    return m;
}

StatusData from_msg(const msg::Status& m) {
    StatusData s;
    s.stamp = m.header.stamp;
    s.frame_id = to_string(m.header.frame_id);
    s.component = to_string(m.component);
    s.level = static_cast<StatusLevel>(m.level);
    s.code = common::status_code_from_wire(m.code);
    s.message = to_string(m.message);
    s.segment = m.segment;
    s.request_id = m.request_id;
    return s;
}

}  // namespace ltm::convert
