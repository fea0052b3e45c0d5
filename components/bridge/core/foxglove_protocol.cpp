#include "bridge/core/foxglove_protocol.hpp"

#include <nlohmann/json.hpp>

namespace ltm::bridge {

using nlohmann::json;

std::string server_info_json(const std::string& name) {
    return json{{"op", "serverInfo"},
                {"name", name},
                {"capabilities", json::array()},
                {"supportedEncodings", json::array({"cdr"})},
                {"metadata", json::object()}}
        .dump();
}

std::string advertise_json(const std::vector<Channel>& channels) {
    json list = json::array();
    for (const Channel& c : channels) {
        list.push_back({{"id", c.id},
                        {"topic", c.topic},
                        {"encoding", c.encoding},
                        {"schemaName", c.schema_name},
                        {"schema", c.schema},
                        {"schemaEncoding", c.schema_encoding}});
    }
    return json{{"op", "advertise"}, {"channels", list}}.dump();
}

std::string unadvertise_json(const std::vector<std::uint32_t>& channel_ids) {
    return json{{"op", "unadvertise"}, {"channelIds", channel_ids}}.dump();
}

std::string status_json(int level, const std::string& message) {
    return json{{"op", "status"}, {"level", level}, {"message", message}}.dump();
}

ClientOp parse_client_message(const std::string& text) {
    ClientOp op;
    try {
        const json j = json::parse(text);
        const std::string name = j.at("op").get<std::string>();
        if (name == "subscribe") {
            op.kind = ClientOp::Kind::kSubscribe;
            for (const json& s : j.at("subscriptions")) {
                op.subscribe.push_back(
                    {s.at("id").get<std::uint32_t>(), s.at("channelId").get<std::uint32_t>()});
            }
        } else if (name == "unsubscribe") {
            op.kind = ClientOp::Kind::kUnsubscribe;
            for (const json& id : j.at("subscriptionIds")) {
                op.unsubscribe.push_back(id.get<std::uint32_t>());
            }
        }
    } catch (const json::exception& e) {
        op = ClientOp{};
        op.kind = ClientOp::Kind::kInvalid;
        op.problem = std::string("not a Foxglove client message: ") + e.what();
    }
    return op;
}

std::string message_data_frame(std::uint32_t subscription_id, std::uint64_t time_ns,
                               const std::uint8_t* payload, std::size_t size) {
    std::string frame(1 + 4 + 8 + size, '\0');
    frame[0] = 0x01;
    for (int i = 0; i < 4; ++i)
        frame[1 + i] = static_cast<char>((subscription_id >> (8 * i)) & 0xff);
    for (int i = 0; i < 8; ++i) frame[5 + i] = static_cast<char>((time_ns >> (8 * i)) & 0xff);
    if (size > 0) frame.replace(13, size, reinterpret_cast<const char*>(payload), size);
    return frame;
}

}  // namespace ltm::bridge
