#include "mesh/component/mesh_params.hpp"

namespace ltm::mesh {

MeshComponentConfig load_mesh_params(runtime::Parameters& p) {
    MeshComponentConfig c;
    c.mesh_file = p.path("mesh_file", "", runtime::PathCheck::kNone);
    c.frame_id = p.get<std::string>("frame_id", c.frame_id);
    if (c.frame_id.empty()) p.fail("frame_id", "must not be empty");
    c.max_queue = p.get<int>("max_queue", c.max_queue);
    if (c.max_queue < 1) p.fail("max_queue", "must be >= 1");
    c.skip_while_busy = p.get<bool>("skip_while_busy", c.skip_while_busy);
    visit_fields(c.mesh, "", [&](const std::string& key, auto& field, const auto& /*rule*/) {
        field = p.get(key, field);
    });
    if (const auto problem = validate(c.mesh)) p.fail(problem->key, problem->problem);
    return c;
}

}  // namespace ltm::mesh
