#pragma once
// What the host-level tests share: where the host binaries, the launch configs and the
// simulator's scenarios are, and the head of a test's launch config (the loopback interface with
// a unicast peer and no multicast: the tests keep to this machine).
#include <string>

namespace ltm::tests {

inline const std::string kHost = std::string(LTM_BINARY_DIR) + "/bin/ltm_host";
inline const std::string kTestHost = std::string(LTM_BINARY_DIR) + "/tests/ltm_test_host";
inline const std::string kConfigs = std::string(LTM_SOURCE_DIR) + "/launch_configs/";
inline const std::string kLoopbackDds = "{interfaces: [lo], multicast: false, peers: [127.0.0.1]}";

// A simulator scenario by its file name ("tiny_loop.yaml").
inline std::string scenario(const std::string& file) {
    return std::string(LTM_SOURCE_DIR) + "/components/simulator/scenarios/" + file;
}

// A launch config up to `components:`: the domain, the loopback DDS, the namespace (none when
// empty), the `topics:` map's entries and the `qos:` map's entries (none when empty).
inline std::string launch_header(int domain, const std::string& ns, const std::string& topics,
                                 const std::string& qos = "") {
    std::string h = "domain_id: " + std::to_string(domain) + "\ndds: " + kLoopbackDds + "\n";
    if (!ns.empty()) h += "namespace: " + ns + "\n";
    h += "topics: {" + topics + "}\n";
    if (!qos.empty()) h += "qos: {" + qos + "}\n";
    return h + "components:\n";
}

}  // namespace ltm::tests
