#include "runtime/worker.hpp"

#include <pthread.h>

namespace ltm::runtime {

std::string worker_thread_name(const std::string& component, const std::string& role) {
    constexpr std::size_t kMax = 15;  // Linux: 16 bytes with the terminating zero
    const std::string tail = "/" + role.substr(0, kMax - 2);
    return component.substr(0, kMax - tail.size()) + tail;
}

std::string component_thread_name(const std::string& component) { return component.substr(0, 15); }

void set_current_thread_name(const std::string& name) {
    pthread_setname_np(pthread_self(), name.substr(0, 15).c_str());
}

}  // namespace ltm::runtime
