#pragma once
// Which component and role a thread of the host works for, from its name (runtime/worker.hpp's
// scheme: "name" = the component's own thread, "name/role" = its worker; names cut to 15
// characters, matched against the launch config's component names).
#include <string>
#include <vector>

namespace ltm::bench {

struct ThreadOwner {
    std::string component;  // a launch config's component, "a|b" when the cut name fits both,
                            // "dds" (Cyclone's own threads), "host" (the host's main thread) or
                            // "other"
    std::string role;       // "main" (a component's own thread), the worker's role, or the name
    std::string key() const { return component + "/" + role; }
};

ThreadOwner thread_owner(const std::string& thread_name,
                         const std::vector<std::string>& components);

// Cyclone DDS's thread names (gc, dq.builtins, dq.user, tev, lease, recv, recvMC, recvUC, xmit.*).
bool is_dds_thread(const std::string& thread_name);

}  // namespace ltm::bench
