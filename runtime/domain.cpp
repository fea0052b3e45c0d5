#include "runtime/domain.hpp"

#include <cmath>
#include <cstdlib>
#include <stdexcept>

#include "runtime/dds_error.hpp"
#include "runtime/dds_security.hpp"
#include "runtime/logging.hpp"
#include "runtime/topic_names.hpp"

namespace ltm::runtime {

namespace {

std::string bytes(std::int64_t b) { return std::to_string(b) + " B"; }
std::string duration(double s) { return std::to_string(std::llround(s * 1e9)) + " ns"; }

// `<Name>text</Name>` when the setting is given.
template <class T, class F>
std::string element(const char* name, const std::optional<T>& value, F text) {
    if (!value) return "";
    return std::string("<") + name + ">" + text(*value) + "</" + name + ">";
}

}  // namespace

std::string cyclone_xml(const DdsSettings& dds) {
    // Socket buffers large enough for bursts of 1-2 MB scans (the OS may grant less: rmem_max).
    // Warnings off: a writer waiting for a full keep-all reader (the `stream` role's intended
    // back-pressure) would be reported every max_blocking_s. Errors still show.
    // The element names are Cyclone DDS 0.10's; the launch config's link settings
    // (launch_config.hpp) go in the same <General> and <Internal> as ltm's own.
    const auto str = [](const std::string& v) { return v; };
    std::string xml = "<CycloneDDS><Domain Id=\"any\"><Internal><SocketReceiveBufferSize max=\"" +
                      (dds.socket_receive_buffer_size ? bytes(*dds.socket_receive_buffer_size)
                                                      : std::string("8MiB")) +
                      "\"/>";
    if (dds.socket_send_buffer_size)
        xml += "<SocketSendBufferSize max=\"" + bytes(*dds.socket_send_buffer_size) + "\"/>";
    xml += element("HeartbeatInterval", dds.heartbeat_interval_s, duration) +
           element("NackDelay", dds.nack_delay_s, duration) +
           element("RetransmitMerging", dds.retransmit_merging, str);
    if (dds.whc_low || dds.whc_high || dds.whc_high_init || dds.whc_adaptive)
        xml += "<Watermarks>" + element("WhcLow", dds.whc_low, bytes) +
               element("WhcHigh", dds.whc_high, bytes) +
               element("WhcHighInit", dds.whc_high_init, bytes) +
               element("WhcAdaptive", dds.whc_adaptive,
                       [](bool b) { return std::string(b ? "true" : "false"); }) +
               "</Watermarks>";
    xml += element("WriterLingerDuration", dds.writer_linger_s, duration);
    xml += "</Internal><Tracing><Verbosity>severe</Verbosity></Tracing>";
    if (!dds.custom) return xml + "</Domain></CycloneDDS>";
    xml += "<General>";
    if (!dds.interfaces.empty()) {
        xml += "<Interfaces>";
        for (const auto& i : dds.interfaces) xml += "<NetworkInterface name=\"" + i + "\"/>";
        xml += "</Interfaces>";
        // Loopback only: large datagrams cost nothing there and cut per-fragment overhead.
        if (dds.interfaces.size() == 1 && dds.interfaces[0] == "lo" && !dds.max_message_size)
            xml += "<MaxMessageSize>65000B</MaxMessageSize>";
    }
    xml += std::string("<AllowMulticast>") + (dds.multicast ? "default" : "false") +
           "</AllowMulticast>";
    xml += element("FragmentSize", dds.fragment_size, bytes) +
           element("MaxMessageSize", dds.max_message_size, bytes) +
           element("MaxRexmitMessageSize", dds.max_retransmit_message_size, bytes);
    xml += "</General><Discovery>";
    if (!dds.peers.empty()) {
        xml += "<ParticipantIndex>auto</ParticipantIndex><MaxAutoParticipantIndex>" +
               std::to_string(dds.max_participant_index) + "</MaxAutoParticipantIndex><Peers>";
        for (const auto& p : dds.peers) xml += "<Peer Address=\"" + p + "\"/>";
        xml += "</Peers>";
    }
    xml += "</Discovery>";
    if (dds.security.enabled()) xml += dds_security_xml(dds.security);
    xml += dds.extra_xml + "</Domain></CycloneDDS>";
    return xml;
}

namespace {

// Cyclone's own log lines through ltm's logger ("warn  [dds] ..."). A reliable writer blocked by a
// full keep-all reader is the `stream` role's intended back-pressure (the write is retried), not
// a problem: Cyclone's warning about it is dropped.
void cyclone_log(void*, const dds_log_data_t* data) {
    // The text after Cyclone's own header (time, domain, thread).
    // Cyclone 0.10 passes the message without that header but with its size in hdrsize; skipping it
    // drops a configuration error's "config: //CycloneDDS/Domain/...:" prefix by coincidence and
    // cuts others mid-word ("icate not valid"): skip only when it ends at a ": ".
    std::size_t skip = data->hdrsize < data->size ? data->hdrsize : 0;
    if (skip < 1 || data->message[skip - 1] != ':' || data->message[skip] != ' ') skip = 0;
    std::string message(data->message + skip, data->size - skip);
    while (!message.empty() && (message.back() == '\n' || message.back() == ' '))
        message.pop_back();
    message.erase(0, message.find_first_not_of(' '));
    if (message.find("could not deliver data on time") != std::string::npos) return;
    const bool error = (data->priority & (DDS_LC_ERROR | DDS_LC_FATAL)) != 0;
    log(error ? LogLevel::kError : LogLevel::kWarn, "dds", message);
}

}  // namespace

Domain::Domain(const LaunchConfig& config) : config_(config), domain_id_(config.domain_id) {
    dds_set_log_sink(&cyclone_log, nullptr);
    // ltm's settings first, then CYCLONEDDS_URI's (the user's word wins), then the launch config's.
    std::string xml = cyclone_xml(DdsSettings{});
    if (const char* uri = std::getenv("CYCLONEDDS_URI"); uri && *uri) xml += std::string(",") + uri;
    if (config.dds.custom) xml += "," + cyclone_xml(config.dds);
    domain_ = dds_create_domain(static_cast<dds_domainid_t>(domain_id_), xml.c_str());
    check_dds(domain_, "creating DDS domain " + std::to_string(domain_id_) +
                           " (launch config dds settings, CYCLONEDDS_URI)");
    participant_ =
        dds_create_participant(static_cast<dds_domainid_t>(domain_id_), nullptr, nullptr);
    if (participant_ < 0) {
        const dds_return_t rc = participant_;
        if (domain_ > 0) dds_delete(domain_);
        throw DdsError("creating the DDS participant on domain " + std::to_string(domain_id_) +
                           (config.dds.security.enabled()
                                ? " (dds.security: a certificate, key or signed document was "
                                  "refused; the [dds] error above says which)"
                                : ""),
                       rc);
    }
}

Domain::~Domain() {
    dds_delete(participant_);
    if (domain_ > 0) dds_delete(domain_);
}

dds_entity_t Domain::topic(const std::string& dds_name, const dds_topic_descriptor_t* desc) {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = topics_.find(dds_name);
    if (it != topics_.end()) {
        if (it->second.second != desc)
            throw std::invalid_argument("topic '" + dds_name + "' already has type " +
                                        it->second.second->m_typename + ", not " +
                                        desc->m_typename);
        return it->second.first;
    }
    const dds_entity_t t = dds_create_topic(participant_, desc, dds_name.c_str(), nullptr, nullptr);
    check_dds(t, "creating topic " + dds_name + " (" + desc->m_typename + ")");
    topics_[dds_name] = {t, desc};
    return t;
}

TopicRole Domain::role(const std::string& absolute_name, TopicRole declared) const {
    const TopicQos* q = topic_qos(absolute_name);
    return q && q->role ? *q->role : declared;
}

QosProfile Domain::profile(const std::string& absolute_name, TopicRole declared) const {
    const QosProfile base = config_.qos.at(role(absolute_name, declared));
    const TopicQos* q = topic_qos(absolute_name);
    return q ? q->apply(base) : base;
}

const TopicQos* Domain::topic_qos(const std::string& absolute_name) const {
    for (const auto& [name, q] : config_.topics) {
        std::string err;
        if (resolve_name(name, config_.ns, "", err) == absolute_name) return &q;
    }
    return nullptr;
}

}  // namespace ltm::runtime
