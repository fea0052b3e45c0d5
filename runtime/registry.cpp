#include "runtime/registry.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>

namespace ltm::runtime {

ComponentRegistry& ComponentRegistry::instance() {
    static ComponentRegistry registry;
    return registry;
}

bool ComponentRegistry::add(ComponentInfo info) {
    if (find(info.type)) {
        std::fprintf(stderr, "ltm: component type '%s' registered twice\n", info.type.c_str());
        std::abort();  // a build mistake, caught by every test that starts a host
    }
    infos_.push_back(std::move(info));
    return true;
}

const ComponentInfo* ComponentRegistry::find(const std::string& type) const {
    for (const auto& i : infos_)
        if (i.type == type) return &i;
    return nullptr;
}

std::vector<const ComponentInfo*> ComponentRegistry::all() const {
    std::vector<const ComponentInfo*> out;
    for (const auto& i : infos_) out.push_back(&i);
    std::sort(out.begin(), out.end(), [](auto* a, auto* b) { return a->type < b->type; });
    return out;
}

}  // namespace ltm::runtime
