// foxglove_bridge: the live topics to Foxglove (desktop or web) over the Foxglove WebSocket
// protocol, without ROS: every ROS-mapped topic on the domain (or the `topics` given) is
// advertised with a schema Foxglove decodes (ros2msg for ROS 2's types, ltm's IDL as omgidl for
// its own) and sent as the CDR it carried on DDS, unchanged; the map as a decimated cloud and the
// mesh chunks as scene entities are made here (scene_topics). A slow client drops messages (it is
// told, the log says so every few seconds), big messages go at most `big_rate_hz` a client; the
// pipeline never waits for a client. Off under DDS Security unless `enable_with_security`.
// Connect Foxglove to ws://HOST:8765.
#define ASIO_STANDALONE
#include <pthread.h>

#include <atomic>
#include <chrono>
#include <future>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <thread>
#include <websocketpp/config/asio_no_tls.hpp>
#include <websocketpp/server.hpp>

#include "bridge/component/scene_topics.hpp"
#include "bridge/core/foxglove_protocol.hpp"
#include "bridge/core/ros2msg_schemas.hpp"
#include "bridge/core/send_policy.hpp"
#include "runtime/component.hpp"
#include "runtime/idl_schema.hpp"
#include "runtime/messages.hpp"

namespace ltm::bridge {
namespace {

using Server = websocketpp::server<websocketpp::config::asio>;
using Connection = websocketpp::connection_hdl;
using runtime::QosProfile;

double now_s() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

std::uint64_t now_ns() {
    return static_cast<std::uint64_t>(std::chrono::duration_cast<std::chrono::nanoseconds>(
                                          std::chrono::system_clock::now().time_since_epoch())
                                          .count());
}

struct Client {
    std::map<std::uint32_t, std::uint32_t> subscription_by_channel;  // channel -> subscription
    SendPolicy policy;
    std::uint64_t reported_drops = 0;
    std::string peer;                 // "127.0.0.1:51234", for the log
    std::uint64_t logged_drops = 0;   // drops the log has counted
    double drops_logged_at_s = -1e9;  // when it last said so
};

constexpr double kDropLogPeriodS = 5.0;

class FoxgloveBridge : public runtime::Component {
  public:
    explicit FoxgloveBridge(runtime::ComponentContext& ctx) : ctx_(ctx) {
        auto& p = ctx.params();
        const int port = p.get<int>("port", 8765);
        if (port < 0 || port > 65535) p.fail("port", "must be 0..65535");
        address_ = p.get<std::string>("address", "127.0.0.1");
        name_ = p.get<std::string>("name", "ltm");
        for (const std::string& t : p.get<std::vector<std::string>>("topics", {})) {
            wanted_.insert(t.rfind("rt/", 0) == 0 ? t : "rt" + (t.front() == '/' ? t : "/" + t));
        }
        policy_.big_message_bytes =
            static_cast<std::size_t>(p.get<double>("big_message_kb", 100.0) * 1024.0);
        policy_.big_rate_hz = p.get<double>("big_rate_hz", 5.0);
        policy_.max_buffered_bytes =
            static_cast<std::size_t>(p.get<double>("max_client_buffer_mb", 8.0) * 1048576.0);
        if (policy_.big_rate_hz < 0.0) p.fail("big_rate_hz", "must be >= 0 (0: no limit)");
        const SceneConfig scene = load_scene_config(p);
        // DDS Security keeps strangers off the site's DDS; the bridge has no authentication and
        // would hand its data to whoever reaches the port, so it is off unless asked for.
        const bool with_security = p.get<bool>("enable_with_security", false);
        if (ctx.launch_config().dds.security.enabled() && !with_security) {
            off_ =
                "the Foxglove bridge is off: this site runs DDS Security and the bridge has no "
                "authentication (set enable_with_security: true to serve it anyway)";
            ctx.log().info(off_);
            return;
        }

        server_.clear_access_channels(websocketpp::log::alevel::all);
        server_.clear_error_channels(websocketpp::log::elevel::all);
        server_.init_asio();
        server_.set_reuse_addr(true);
        server_.set_validate_handler([this](Connection h) { return validate(h); });
        server_.set_open_handler([this](Connection h) { on_open(h); });
        server_.set_close_handler([this](Connection h) { on_close(h); });
        server_.set_message_handler(
            [this](Connection h, Server::message_ptr m) { on_message(h, m->get_payload()); });
        // A port in use or an address not here turns the bridge off with one warning: the live
        // view is not worth stopping the robot's mission for.
        websocketpp::lib::error_code ec;
        const auto address = asio::ip::make_address(address_, ec);
        if (ec) p.fail("address", "not an IP address: " + address_);
        server_.listen(asio::ip::tcp::endpoint(address, static_cast<unsigned short>(port)), ec);
        if (!ec) server_.start_accept(ec);
        if (ec) {
            off_ = "cannot listen on " + address_ + ":" + std::to_string(port) + " (" +
                   ec.message() + "): the Foxglove bridge is off (set its port)";
            ctx.log().warn(off_);
            return;
        }
        port_ = server_.get_local_endpoint(ec).port();
        if (address_ != "127.0.0.1" && address_ != "localhost" && address_ != "::1") {
            ctx.log().warn("the Foxglove bridge listens on " + address_ +
                           ": every host that reaches it sees the robot's data (no "
                           "authentication); 127.0.0.1 keeps it on this machine");
        }
        const dds_entity_t reader = dds_create_reader(
            ctx.participant(), DDS_BUILTIN_TOPIC_DCPSPUBLICATION, nullptr, nullptr);
        if (reader < 0) {
            throw std::runtime_error(std::string("cannot read DCPSPublication: ") +
                                     dds_strretcode(reader));
        }
        ctx.subscribe_reader(reader, [this](const void* s) {
            on_publication(*static_cast<const dds_builtintopic_endpoint_t*>(s));
        });
        scene_ = std::make_unique<SceneTopics>(
            ctx, scene, next_channel_,
            [this](std::uint32_t channel, std::shared_ptr<const std::vector<std::uint8_t>> cdr,
                   const std::string& key) {
                const std::uint64_t t = now_ns();
                asio::post(server_.get_io_service(), [this, channel, cdr, key, t] {
                    latched_[channel][key] = {cdr, t};
                    deliver(channel, cdr, t);
                });
            });
        for (const Channel& c : scene_->channels()) {
            channels_[c.id] = c;
            next_channel_ = c.id + 1;
            // Mesh chunks: each one its own entity, never replaced by the next message.
            if (c.id != scene_->map_channel()) keyed_.insert(c.id);
        }
        ctx.add_timer(10.0, [this] { report(); });
        // Named as runtime::Worker names its threads ("bridge/io"), so `./ltm bench budget`
        // and `./ltm bench bridge` count its CPU time to the bridge.
        thread_ = std::thread([this, name = ctx.name() + "/io"] {
            pthread_setname_np(pthread_self(), name.substr(0, 15).c_str());
            server_.run();
        });
    }

    ~FoxgloveBridge() override { stop(); }

    void on_activate() override {
        if (!off_.empty()) return;
        ctx_.log().info("Foxglove: connect to ws://" +
                        (address_ == "0.0.0.0" ? std::string("ROBOT") : address_) + ":" +
                        std::to_string(port_) + " (Foxglove WebSocket, " + kSubprotocol + ")");
    }

    void on_shutdown() override {
        report();
        stop();
    }

  private:
    bool validate(Connection h) {
        const auto con = server_.get_con_from_hdl(h);
        for (const std::string& p : con->get_requested_subprotocols()) {
            if (p == kSubprotocol) {
                con->select_subprotocol(p);
                return true;
            }
        }
        return false;
    }

    // io thread
    void on_open(Connection h) {
        clients_[h].policy = SendPolicy(policy_);
        {
            websocketpp::lib::error_code ec;
            const auto con = server_.get_con_from_hdl(h, ec);
            if (!ec) clients_[h].peer = con->get_remote_endpoint();
        }
        ++open_clients_;
        send_text(h, server_info_json(name_));
        std::vector<Channel> channels;
        {
            std::lock_guard<std::mutex> lock(channels_mutex_);
            for (const auto& [id, c] : channels_) channels.push_back(c);
        }
        if (!channels.empty()) send_text(h, advertise_json(channels));
        ++connections_;
    }

    // io thread
    void on_close(Connection h) {
        const auto it = clients_.find(h);
        if (it == clients_.end()) return;
        if (scene_ && it->second.subscription_by_channel.count(scene_->map_channel()))
            --scene_->map_watchers();
        const std::map<std::uint32_t, std::uint32_t> left = it->second.subscription_by_channel;
        clients_.erase(it);
        for (const auto& [channel, subscription] : left) watch(channel);
        --open_clients_;
    }

    // io thread
    void on_message(Connection h, const std::string& text) {
        const auto it = clients_.find(h);
        if (it == clients_.end()) return;
        const ClientOp op = parse_client_message(text);
        if (op.kind == ClientOp::Kind::kInvalid) {
            send_text(h, status_json(2, op.problem));
        } else if (op.kind == ClientOp::Kind::kSubscribe) {
            for (const auto& s : op.subscribe) {
                const bool added =
                    it->second.subscription_by_channel.insert_or_assign(s.channel_id, s.id).second;
                if (added && scene_ && s.channel_id == scene_->map_channel())
                    ++scene_->map_watchers();
                watch(s.channel_id);
                // What a latching channel sent before: the map cloud, every mesh chunk.
                const auto l = latched_.find(s.channel_id);
                if (l == latched_.end()) continue;
                for (const auto& [key, m] : l->second) send_to(h, it->second, s.channel_id, m);
            }
        } else if (op.kind == ClientOp::Kind::kUnsubscribe) {
            for (const std::uint32_t id : op.unsubscribe) {
                for (auto s = it->second.subscription_by_channel.begin();
                     s != it->second.subscription_by_channel.end();) {
                    if (s->second != id) {
                        ++s;
                        continue;
                    }
                    if (scene_ && s->first == scene_->map_channel()) --scene_->map_watchers();
                    const std::uint32_t channel = s->first;
                    s = it->second.subscription_by_channel.erase(s);
                    watch(channel);
                }
                it->second.policy.forget(id);
            }
        }
    }

    // io thread: whether any client subscribes to `channel` now, for the DDS handlers.
    void watch(std::uint32_t channel) {
        bool any = false;
        for (const auto& [h, client] : clients_)
            any = any || client.subscription_by_channel.count(channel);
        std::lock_guard<std::mutex> lock(watched_mutex_);
        if (any) {
            watched_.insert(channel);
        } else {
            watched_.erase(channel);
        }
    }
    // component thread: a sample of a channel no client subscribes to is not copied (a robot's
    // bridge with no Foxglove open copied every scan, ~1 ms of CPU a scan: issue 28).
    bool watched(std::uint32_t channel) {
        std::lock_guard<std::mutex> lock(watched_mutex_);
        return watched_.count(channel) > 0;
    }

    struct Latched {
        std::shared_ptr<const std::vector<std::uint8_t>> cdr;
        std::uint64_t time_ns = 0;
    };

    // io thread: one DDS sample to every client subscribed to its channel.
    void deliver(std::uint32_t channel, const std::shared_ptr<const std::vector<std::uint8_t>>& cdr,
                 std::uint64_t time_ns) {
        for (auto& [h, client] : clients_) {
            if (client.subscription_by_channel.count(channel))
                send_to(h, client, channel, {cdr, time_ns});
        }
    }

    // io thread: one message to one client's subscription of `channel`, as its policy allows.
    void send_to(Connection h, Client& client, std::uint32_t channel, const Latched& m) {
        const std::uint32_t subscription = client.subscription_by_channel.at(channel);
        websocketpp::lib::error_code ec;
        const auto con = server_.get_con_from_hdl(h, ec);
        if (ec) return;
        const double now = now_s();
        const SendPolicy::Verdict v =
            client.policy.decide(subscription, m.cdr->size(), now, con->get_buffered_amount(),
                                 keyed_.count(channel) == 0);
        if (v == SendPolicy::Verdict::kBacklogged) {
            ++dropped_;
            const std::uint64_t drops = client.policy.backlogged();
            if (drops >= client.reported_drops * 2 + 1) {  // 1, 3, 7, ...: said, not spammed
                client.reported_drops = drops;
                send_text(h, status_json(1, "this client is too slow: " + std::to_string(drops) +
                                                " messages dropped so far"));
            }
            if (now - client.drops_logged_at_s >= kDropLogPeriodS) {  // once every few seconds
                ctx_.log().warn("Foxglove client " + client.peer +
                                " is too slow: " + std::to_string(drops - client.logged_drops) +
                                " messages dropped since the last report (" +
                                std::to_string(drops) + " in all, " +
                                std::to_string(con->get_buffered_amount() >> 10) +
                                " kB waiting in its socket)");
                client.logged_drops = drops;
                client.drops_logged_at_s = now;
            }
            return;
        }
        if (v == SendPolicy::Verdict::kRateLimited) return;
        const std::string frame =
            message_data_frame(subscription, m.time_ns, m.cdr->data(), m.cdr->size());
        server_.send(h, frame, websocketpp::frame::opcode::binary, ec);
        if (!ec) ++sent_;
    }

    void send_text(Connection h, const std::string& text) {
        websocketpp::lib::error_code ec;
        server_.send(h, text, websocketpp::frame::opcode::text, ec);
    }

    // component thread
    void on_publication(const dds_builtintopic_endpoint_t& pub) {
        const std::string topic = pub.topic_name ? pub.topic_name : "";
        const std::string type = pub.type_name ? pub.type_name : "";
        if (topic.rfind("rt/", 0) != 0) return;
        if (!wanted_.empty() && !wanted_.count(topic)) return;
        if (seen_.count(topic)) return;
        seen_.insert(topic);
        const runtime::MessageTypeInfo* info = runtime::find_message_type_by_dds_name(type);
        if (!info) {
            ctx_.log().warn("not bridging " + topic + ": type " + type + " is unknown to ltm");
            return;
        }
        // Never a reader that holds a writer back: best effort unless the writer is reliable, and
        // then a shallow keep-last (a late sample replaces an old one).
        QosProfile qos = runtime::matching_reader_profile(pub.qos, 4);
        if (qos.transient_local) qos.depth = 16;
        Channel c;
        c.id = next_channel_++;
        c.topic = topic.substr(2);
        // ROS 2's own types by their ROS names (Foxglove draws them: PointCloud2, TFMessage,
        // Odometry, Path, ...); ltm's own types with their IDL.
        c.schema = ros2msg_schema(info->ros_name);
        if (!c.schema.empty()) {
            c.schema_name = info->ros_name;
            c.schema_encoding = "ros2msg";
        } else {
            c.schema_name = info->dds_name;
            c.schema = runtime::idl_schema_text(info->ros_name);
        }
        {
            std::lock_guard<std::mutex> lock(channels_mutex_);
            channels_[c.id] = c;
        }
        const std::uint32_t id = c.id;
        // A transient-local topic (tf_static, path, pose graph, local maps) keeps each writer's
        // last message for a client that subscribes later, as DDS does for a late reader.
        const bool latch = qos.transient_local;
        ctx_.subscribe_raw(
            topic.substr(2), info->descriptor, qos,
            [this, id, latch](const std::vector<std::uint8_t>& cdr, const dds_sample_info_t& i) {
                // Latched samples are kept for a client that subscribes later; the others go
                // only to the clients subscribed now.
                if (!latch && !watched(id)) return;
                auto shared = std::make_shared<const std::vector<std::uint8_t>>(cdr);
                // The message's time: its DDS source timestamp (the writer's clock, this host's
                // in one process), so a client reads the delivery latency; the bridge's receipt
                // time where a writer gave none.
                const std::uint64_t t = i.source_timestamp > 0
                                            ? static_cast<std::uint64_t>(i.source_timestamp)
                                            : now_ns();
                const std::string writer = latch ? std::to_string(i.publication_handle) : "";
                asio::post(server_.get_io_service(), [this, id, shared, t, writer] {
                    if (!writer.empty()) latched_[id][writer] = {shared, t};
                    deliver(id, shared, t);
                });
            });
        asio::post(server_.get_io_service(), [this, c] {
            for (auto& [h, client] : clients_) send_text(h, advertise_json({c}));
        });
    }

    void report() {
        const std::uint64_t dropped = dropped_.load();
        if (dropped == reported_dropped_ && connections_ == reported_connections_) return;
        reported_dropped_ = dropped;
        reported_connections_ = connections_;
        const std::string line = "Foxglove: " + std::to_string(connections_.load()) +
                                 " connections so far, " + std::to_string(sent_.load()) +
                                 " messages sent, " + std::to_string(dropped) +
                                 " dropped for slow clients";
        (dropped > 0 ? ctx_.log().warn(line) : ctx_.log().info(line));
    }

    void stop() {
        if (!thread_.joinable()) return;  // never started (off) or stopped
        asio::post(server_.get_io_service(), [this] {
            websocketpp::lib::error_code ec;
            server_.stop_listening(ec);
            for (auto& [h, client] : clients_)
                server_.close(h, websocketpp::close::status::going_away, "ltm stops", ec);
        });
        // The closing handshakes have a moment; then the loop ends regardless.
        for (int i = 0; i < 20 && !server_.stopped(); ++i) {
            std::this_thread::sleep_for(std::chrono::milliseconds(25));
            if (clients_empty()) break;
        }
        server_.stop();
        thread_.join();
    }

    bool clients_empty() {
        // Shared: the io thread may answer after this wait gave up.
        auto empty = std::make_shared<std::promise<bool>>();
        auto f = empty->get_future();
        asio::post(server_.get_io_service(), [this, empty] { empty->set_value(clients_.empty()); });
        return f.wait_for(std::chrono::milliseconds(100)) == std::future_status::ready && f.get();
    }

    runtime::ComponentContext& ctx_;
    Server server_;
    std::thread thread_;
    std::string address_, name_, off_;
    unsigned short port_ = 0;
    SendPolicyConfig policy_;
    std::set<std::string> wanted_, seen_;
    std::mutex channels_mutex_;
    std::map<std::uint32_t, Channel> channels_;
    std::uint32_t next_channel_ = 1;
    std::map<Connection, Client, std::owner_less<Connection>> clients_;  // io thread only
    std::unique_ptr<SceneTopics> scene_;
    std::set<std::uint32_t> keyed_;  // not rate limited; set before the io thread starts
    std::map<std::uint32_t, std::map<std::string, Latched>> latched_;  // io thread only
    std::atomic<std::uint64_t> sent_{0}, dropped_{0}, connections_{0};
    std::atomic<int> open_clients_{0};
    std::mutex watched_mutex_;
    std::set<std::uint32_t> watched_;  // channels some client subscribes to (io thread writes)
    std::uint64_t reported_dropped_ = 0, reported_connections_ = 0;
};

}  // namespace
}  // namespace ltm::bridge

LTM_REGISTER_COMPONENT(
    ltm::bridge::FoxgloveBridge, "foxglove_bridge",
    "live topics to Foxglove over the Foxglove WebSocket protocol (ws://HOST:8765)")
