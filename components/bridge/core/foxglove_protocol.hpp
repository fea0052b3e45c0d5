#pragma once
// The Foxglove WebSocket protocol (foxglove.websocket.v1), server side, without a socket: the JSON
// a server sends (serverInfo, advertise, unadvertise, status), the client's operations it reads
// (subscribe, unsubscribe) and the binary message-data frame. The socket is the component's.
#include <cstdint>
#include <string>
#include <vector>

namespace ltm::bridge {

constexpr const char* kSubprotocol = "foxglove.websocket.v1";

struct Channel {
    std::uint32_t id = 0;
    std::string topic;             // as Foxglove shows it: "/robot/odometry"
    std::string encoding = "cdr";  // the payload: the CDR DDS carried, unchanged
    std::string schema_name;       // "nav_msgs::msg::dds_::Odometry_"
    std::string schema;            // its IDL text
    std::string schema_encoding = "omgidl";
};

std::string server_info_json(const std::string& name);
std::string advertise_json(const std::vector<Channel>& channels);
std::string unadvertise_json(const std::vector<std::uint32_t>& channel_ids);
// level: 0 info, 1 warning, 2 error.
std::string status_json(int level, const std::string& message);

struct ClientOp {
    enum class Kind { kSubscribe, kUnsubscribe, kIgnored, kInvalid };
    Kind kind = Kind::kIgnored;
    struct Subscription {
        std::uint32_t id = 0, channel_id = 0;
    };
    std::vector<Subscription> subscribe;     // kSubscribe
    std::vector<std::uint32_t> unsubscribe;  // kUnsubscribe: subscription ids
    std::string problem;                     // kInvalid: why, one line
};
// A text frame from a client. Operations this server does not offer (publishing, parameters,
// services) are kIgnored.
ClientOp parse_client_message(const std::string& text);

// Opcode 0x01: subscription id (u32 LE), receive time (u64 LE, ns), payload.
std::string message_data_frame(std::uint32_t subscription_id, std::uint64_t time_ns,
                               const std::uint8_t* payload, std::size_t size);

}  // namespace ltm::bridge
