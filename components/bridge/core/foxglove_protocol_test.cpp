#include "bridge/core/foxglove_protocol.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "bridge/core/send_policy.hpp"

namespace ltm::bridge {
namespace {

using nlohmann::json;

TEST(FoxgloveProtocol, AdvertisesChannelsWithTheirIdlSchema) {
    Channel c;
    c.id = 3;
    c.topic = "/robot/odometry";
    c.schema_name = "nav_msgs::msg::dds_::Odometry_";
    c.schema = "module nav_msgs { };";
    const json a = json::parse(advertise_json({c}));
    EXPECT_EQ(a["op"], "advertise");
    ASSERT_EQ(a["channels"].size(), 1u);
    EXPECT_EQ(a["channels"][0]["id"], 3);
    EXPECT_EQ(a["channels"][0]["encoding"], "cdr");
    EXPECT_EQ(a["channels"][0]["schemaEncoding"], "omgidl");
    EXPECT_EQ(a["channels"][0]["schema"], "module nav_msgs { };");
    const json info = json::parse(server_info_json("ltm"));
    EXPECT_EQ(info["op"], "serverInfo");
    EXPECT_EQ(info["supportedEncodings"][0], "cdr");
    EXPECT_EQ(json::parse(status_json(1, "slow"))["level"], 1);
    EXPECT_EQ(json::parse(unadvertise_json({1, 2}))["channelIds"].size(), 2u);
}

TEST(FoxgloveProtocol, ReadsSubscriptionsAndRefusesGarbage) {
    ClientOp op = parse_client_message(
        R"({"op":"subscribe","subscriptions":[{"id":7,"channelId":3},{"id":8,"channelId":4}]})");
    ASSERT_EQ(op.kind, ClientOp::Kind::kSubscribe);
    ASSERT_EQ(op.subscribe.size(), 2u);
    EXPECT_EQ(op.subscribe[1].id, 8u);
    EXPECT_EQ(op.subscribe[1].channel_id, 4u);
    op = parse_client_message(R"({"op":"unsubscribe","subscriptionIds":[7]})");
    ASSERT_EQ(op.kind, ClientOp::Kind::kUnsubscribe);
    EXPECT_EQ(op.unsubscribe, std::vector<std::uint32_t>{7});
    EXPECT_EQ(parse_client_message(R"({"op":"advertise","channels":[]})").kind,
              ClientOp::Kind::kIgnored);
    for (const char* bad : {"not json", R"({"op":"subscribe"})",
                            R"({"op":"subscribe","subscriptions":[{"id":-1}]})", "[]"}) {
        op = parse_client_message(bad);
        EXPECT_EQ(op.kind, ClientOp::Kind::kInvalid) << bad;
        EXPECT_FALSE(op.problem.empty());
    }
}

TEST(FoxgloveProtocol, MessageDataFrameIsLittleEndian) {
    const std::uint8_t payload[] = {0, 1, 0, 0, 42};
    const std::string f = message_data_frame(0x01020304u, 0x1122334455667788ull, payload, 5);
    ASSERT_EQ(f.size(), 18u);
    EXPECT_EQ(f[0], 0x01);
    EXPECT_EQ(f[1], 0x04);
    EXPECT_EQ(f[4], 0x01);
    EXPECT_EQ(static_cast<unsigned char>(f[5]), 0x88);
    EXPECT_EQ(f[12], 0x11);
    EXPECT_EQ(f[17], 42);
}

TEST(SendPolicy, BigMessagesAreRateLimitedAndABacklogDrops) {
    SendPolicy p({/*big*/ 1000, /*rate*/ 2.0, /*buffer*/ 5000});
    EXPECT_EQ(p.decide(1, 2000, 0.0, 0), SendPolicy::Verdict::kSend);
    EXPECT_EQ(p.decide(1, 2000, 0.2, 0), SendPolicy::Verdict::kRateLimited);
    EXPECT_EQ(p.decide(2, 2000, 0.2, 0), SendPolicy::Verdict::kSend);  // its own subscription
    EXPECT_EQ(p.decide(1, 2000, 0.6, 0), SendPolicy::Verdict::kSend);
    EXPECT_EQ(p.decide(3, 100, 0.6, 0), SendPolicy::Verdict::kSend);  // small: never limited
    EXPECT_EQ(p.decide(3, 100, 0.6, 4950), SendPolicy::Verdict::kBacklogged);
    // One message bigger than the buffer, with nothing waiting: sent (never stuck for ever).
    EXPECT_EQ(p.decide(4, 6000, 0.6, 0), SendPolicy::Verdict::kSend);
    EXPECT_EQ(p.sent(), 5u);
    EXPECT_EQ(p.rate_limited(), 1u);
    EXPECT_EQ(p.backlogged(), 1u);
}

}  // namespace
}  // namespace ltm::bridge
