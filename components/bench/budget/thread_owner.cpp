#include "bench/budget/thread_owner.hpp"

#include "runtime/worker.hpp"

namespace ltm::bench {

bool is_dds_thread(const std::string& n) {
    for (const char* p : {"dq.", "tev", "recv", "xmit", "debmon", "dds"})
        if (n.rfind(p, 0) == 0) return true;
    return n == "gc" || n == "lease";
}

ThreadOwner thread_owner(const std::string& name, const std::vector<std::string>& components) {
    const auto slash = name.find('/');
    const std::string role = slash == std::string::npos ? "main" : name.substr(slash + 1);
    std::string owner;
    for (const auto& c : components) {
        const std::string expected = slash == std::string::npos
                                         ? runtime::component_thread_name(c)
                                         : runtime::worker_thread_name(c, role);
        if (expected != name) continue;
        owner += (owner.empty() ? "" : "|") + c;
    }
    if (!owner.empty()) return {owner, role};
    if (is_dds_thread(name)) return {"dds", name};
    if (name == "ltm_host") return {"host", "main"};
    return {"other", name};
}

}  // namespace ltm::bench
