#pragma once
// The mesh component's parameters: its own keys (where the global mesh goes, the map frame, its
// worker's queue) beside the keys of the core's MeshConfig (`grid_size`, `truncation`, `support`,
// ...: visit_fields in mesh/core/mesh_config.hpp). Wrong types and invalid values fail with file,
// line and key; the host refuses the keys nobody read.
#include <string>

#include "mesh/core/mesh_config.hpp"
#include "runtime/parameters.hpp"

namespace ltm::mesh {

struct MeshComponentConfig {
    // The global mesh (PLY, map frame: every chunk's owned triangles where the graph puts it),
    // written at shutdown and on request (its folder created then). "": only on request, to the
    // file the request names.
    std::string mesh_file;
    std::string frame_id = "map";  // of the published chunks until a pose graph names its own
    int max_queue = 20;            // finished local maps waiting for the worker
    // A full queue drops its oldest map (live: the mesh lags least) or the component's thread
    // waits for room (offline: every map meshed).
    bool skip_while_busy = false;
    MeshConfig mesh;
};

// Throws ConfigError naming file, line and key.
MeshComponentConfig load_mesh_params(runtime::Parameters& params);

}  // namespace ltm::mesh
