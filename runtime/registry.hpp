#pragma once
// Link-time registration of component types (after ros2/demos linktime_composition).
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace ltm::runtime {

class Component;
class ComponentContext;

struct ComponentInfo {
    std::string type;         // name used in launch configs
    std::string description;  // one line for --list-components
    std::function<std::unique_ptr<Component>(ComponentContext&)> make;
};

class ComponentRegistry {
  public:
    static ComponentRegistry& instance();
    bool add(ComponentInfo info);
    const ComponentInfo* find(const std::string& type) const;
    std::vector<const ComponentInfo*> all() const;  // sorted by type

  private:
    std::vector<ComponentInfo> infos_;
};

}  // namespace ltm::runtime

#define LTM_REGISTER_CONCAT_INNER(a, b) a##b
#define LTM_REGISTER_CONCAT(a, b) LTM_REGISTER_CONCAT_INNER(a, b)
// One line at the bottom of a component's .cpp file.
#define LTM_REGISTER_COMPONENT(Class, type_name, description)                       \
    namespace {                                                                     \
    const bool LTM_REGISTER_CONCAT(ltm_registered_component_, __LINE__) =           \
        ::ltm::runtime::ComponentRegistry::instance().add(                          \
            {type_name, description, [](::ltm::runtime::ComponentContext& ctx) {    \
                 return std::unique_ptr<::ltm::runtime::Component>(new Class(ctx)); \
             }});                                                                   \
    }
