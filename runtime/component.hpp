#pragma once
// A component: a thin DDS adapter around a core library, composed into a host process.
//
//   class Writer : public ltm::runtime::Component {
//   public:
//       explicit Writer(ltm::runtime::ComponentContext& ctx) : ctx_(ctx) {
//           path_ = ctx.params().path("path", "out.txt", PathCheck::kParentExists);
//           ctx.subscribe<ltm::msg::Odometry>("odometry", TopicRole::kState,
//                                             [this](const ltm::msg::Odometry& m) { ... });
//       }
//       void on_shutdown() override { /* flush */ }
//   };
//   LTM_REGISTER_COMPONENT(Writer, "trajectory_writer", "writes poses as KITTI/TUM files");
//
// Lifecycle: the constructor configures (reads parameters, declares topics; throws ConfigError or
// any exception to refuse), on_activate / on_deactivate / on_shutdown run on the component's own
// thread. Handlers and timers run on that thread too, one at a time.
#include <atomic>
#include <functional>
#include <memory>
#include <string>

#include "runtime/component_context.hpp"

namespace ltm::runtime {

class Component {
  public:
    virtual ~Component() = default;
    virtual void on_activate() {}
    virtual void on_deactivate() {}
    // Flush outputs, save maps. Also called after a handler threw, before a restart or stop.
    virtual void on_shutdown() {}
};

}  // namespace ltm::runtime

#include "runtime/registry.hpp"
