#pragma once
// ltm_msgs/Status: a component's status line (skipped or rejected frames, answers to requests).
// The line's code is data (common::StatusCode); the message's `key` is its text, set here.
#include <cstdint>
#include <string>

#include "common/core/status_code.hpp"
#include "runtime/convert/owned_message.hpp"
#include "runtime/logging.hpp"
#include "runtime/messages.hpp"

namespace ltm::convert {

enum class StatusLevel : std::uint8_t {
    kOk = ltm_msgs_msg_Status_Constants_OK,
    kWarn = ltm_msgs_msg_Status_Constants_WARN,
    kError = ltm_msgs_msg_Status_Constants_ERROR,
};

struct StatusData {
    msg::Time stamp{};     // zero when the line belongs to no sample
    std::string frame_id;  // the component's frame
    std::string component;
    StatusLevel level = StatusLevel::kOk;
    common::StatusCode code = common::StatusCode::kUnknown;
    std::string message;
    std::uint32_t segment = 0;     // kRestarted: the new odometry segment
    std::uint32_t request_id = 0;  // kMapRequestDone / kMapRequestFailed: the request answered
};

Owned<msg::Status> to_msg(const StatusData& status);

// Logs a status line at its level: info, warn or error.
inline void log_status(const runtime::Logger& log, StatusLevel level, const std::string& text) {
    if (level == StatusLevel::kOk) {
        log.info(text);
    } else if (level == StatusLevel::kError) {
        log.error(text);
    } else {
        log.warn(text);
    }
}
StatusData from_msg(const msg::Status& message);

}  // namespace ltm::convert
