#include "map/core/map_graph.hpp"

namespace ltm::map {

const char* to_string(EdgeKind kind) {
    switch (kind) {
        case EdgeKind::kOdometry:
            return "odometry";
        case EdgeKind::kLoop:
            return "loop";
    }
    return "unknown";
}

}  // namespace ltm::map
