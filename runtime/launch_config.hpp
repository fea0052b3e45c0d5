#pragma once
// The launch config: one host process, its DDS settings and its components (see
// launch_configs/README.md for every key).
#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "runtime/dds_security.hpp"
#include "runtime/log_file.hpp"
#include "runtime/qos.hpp"

namespace ltm::runtime {

struct DdsSettings {
    bool custom = false;                  // false: Cyclone's defaults (CYCLONEDDS_URI honoured)
    std::vector<std::string> interfaces;  // e.g. [lo]
    std::vector<std::string> peers;       // unicast discovery peers, e.g. [127.0.0.1]
    bool multicast = true;
    int max_participant_index = 20;  // unicast discovery probes this many ports a peer
    std::string extra_xml;           // appended inside <Domain>, for anything else
    DdsSecurity security;            // off unless `dds.security` names the files

    // Cyclone settings for a narrow, lossy link; unset: Cyclone's default (the Cyclone DDS 0.10
    // element each one sets in brackets; launch_configs/README.md says when to change them).
    std::optional<std::int64_t> fragment_size;  // [B] General/FragmentSize (1344)
    std::optional<std::int64_t>
        max_message_size;  // [B] General/MaxMessageSize (14720; 65000 on lo)
    std::optional<std::int64_t> max_retransmit_message_size;  // [B] General/MaxRexmitMessageSize
    std::optional<std::int64_t> socket_receive_buffer_size;  // [B] Internal/SocketReceiveBufferSize
    std::optional<std::int64_t> socket_send_buffer_size;     // [B] Internal/SocketSendBufferSize
    std::optional<double> heartbeat_interval_s;              // Internal/HeartbeatInterval (0.1)
    std::optional<double> nack_delay_s;                      // Internal/NackDelay (0.1)
    std::optional<std::string> retransmit_merging;           // Internal/RetransmitMerging (never)
    std::optional<std::int64_t> whc_low;        // [B] Internal/Watermarks/WhcLow (1 KiB)
    std::optional<std::int64_t> whc_high;       // [B] Internal/Watermarks/WhcHigh (500 KiB)
    std::optional<std::int64_t> whc_high_init;  // [B] Internal/Watermarks/WhcHighInit (30 KiB)
    std::optional<bool> whc_adaptive;           // Internal/Watermarks/WhcAdaptive (true)
    std::optional<double> writer_linger_s;      // Internal/WriterLingerDuration (1)
};

struct ComponentSpec {
    std::string name;                           // instance name, unique in the host
    std::string type;                           // registered component type
    YAML::Node params;                          // the `params:` map (may be null)
    std::map<std::string, std::string> remaps;  // declared topic -> new name
    std::map<std::string, int> remap_lines;     // for error messages
    int line = 0;                               // line of the entry
    int type_line = 0;
};

enum class ErrorPolicy { kStop, kRestart };

struct LaunchConfig {
    std::string file;
    int domain_id = 0;
    std::string ns;  // namespace of every relative topic name
    DdsSettings dds;
    std::map<TopicRole, QosProfile> qos;     // a profile for every role
    std::map<std::string, TopicQos> topics;  // topic name -> role and profile overrides
    ErrorPolicy on_error = ErrorPolicy::kStop;
    int max_restarts = 3;
    bool exit_when_sources_done =
        true;  // stop once every source finished and all input is processed
    double idle_exit_s =
        0.0;  // hosts without sources: stop after this long without input (0: never)
    double shutdown_timeout_s = 30.0;  // the stop deadline after SIGINT/SIGTERM (final saves)
    double finish_timeout_s = 60.0;    // after the sources finished or the idle exit (final saves)
    HostLogConfig log;                 // `log:` the host's lines also in a bounded file
    int log_line = 0;
    std::vector<ComponentSpec> components;
};

// Reads and validates a launch config. `overrides` are "--set" arguments: "name.key=value" sets a
// parameter of component `name`, "key=value" a top-level key. Throws ConfigError (file:line: key:).
LaunchConfig load_launch_config(const std::string& path,
                                const std::vector<std::string>& overrides = {});

}  // namespace ltm::runtime
