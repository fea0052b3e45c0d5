#pragma once
// ltm's messages between the base station's link and its mapping, and between a base station's
// mapping and a split robot (issue 28 item 4, issue 26): LinkDelivered (downlink -> mapping: how
// far a robot's packets were handed on) and MapVersion (which site version a mapping's map frame,
// and its map_to_odom, belongs to). Apart from messages.hpp, which every component includes: only
// the few that use them include this; messages.cpp lists them among the known types.
#include "ltm_msgs/msg/LinkDelivered.h"
#include "ltm_msgs/msg/MapVersion.h"
#include "runtime/messages.hpp"

namespace ltm::msg {
using LinkDelivered = ltm_msgs_msg_dds__LinkDelivered_;
using MapVersion = ltm_msgs_msg_dds__MapVersion_;
}  // namespace ltm::msg

namespace ltm::runtime {
LTM_MESSAGE_TRAITS(ltm_msgs_msg_dds__LinkDelivered_, "ltm_msgs/msg/LinkDelivered")
LTM_MESSAGE_TRAITS(ltm_msgs_msg_dds__MapVersion_, "ltm_msgs/msg/MapVersion")
}  // namespace ltm::runtime
