#pragma once
// ltm_msgs/MapChangeSet -> the voxel centres map maintenance removed (moving, vanished) and added
// (new objects), for Mapper::remove_cells / keep_cells. Malformed changes (voxels not x y z
// triples, an unknown reason, a voxel size that is not positive) are counted and left out.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "runtime/messages.hpp"

namespace ltm::mapping {

struct ChangeCells {
    std::vector<Eigen::Vector3f> removed, added;
    // The voxels of each vanished segment (also in `removed`): Mapper::remove_cells' `vanished`.
    std::vector<std::vector<Eigen::Vector3f>> vanished;
    float cell_size = 0.0f;
    std::size_t removed_segments = 0, added_segments = 0, malformed = 0;
    std::string frame_id;
};

ChangeCells change_cells(const msg::MapChangeSet& m);

}  // namespace ltm::mapping
