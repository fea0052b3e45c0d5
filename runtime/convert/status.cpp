#include "runtime/convert/status.hpp"

#include "runtime/convert/dds_string.hpp"

namespace ltm::convert {

Owned<msg::Status> to_msg(const StatusData& s) {
    Owned<msg::Status> m;
    m->header.stamp = s.stamp;
    set_string(m->header.frame_id, s.frame_id);
    set_string(m->component, s.component);
    m->level = static_cast<std::uint8_t>(s.level);
    set_string(m->code, s.code);
    set_string(m->message, s.message);
    return m;
}

StatusData from_msg(const msg::Status& m) {
    StatusData s;
    s.stamp = m.header.stamp;
    s.frame_id = to_string(m.header.frame_id);
    s.component = to_string(m.component);
    s.level = static_cast<StatusLevel>(m.level);
    s.code = to_string(m.code);
    s.message = to_string(m.message);
    return s;
}

}  // namespace ltm::convert
