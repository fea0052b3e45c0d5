#include "mapping/component/map_change_cells.hpp"

#include <cmath>

#include "runtime/convert/dds_string.hpp"

namespace ltm::mapping {

ChangeCells change_cells(const msg::MapChangeSet& m) {
    ChangeCells out;
    out.frame_id = convert::to_string(m.header.frame_id);
    out.cell_size = m.voxel_size;
    if (!(m.voxel_size > 0.0f) || !std::isfinite(m.voxel_size)) {
        out.malformed = m.changes._length;
        return out;
    }
    for (std::uint32_t i = 0; i < m.changes._length; ++i) {
        const auto& c = m.changes._buffer[i];
        std::vector<Eigen::Vector3f>* to = nullptr;
        switch (c.reason) {
            case ltm_msgs_msg_SegmentChange_Constants_MOVING:
            case ltm_msgs_msg_SegmentChange_Constants_VANISHED:
                to = &out.removed;
                ++out.removed_segments;
                break;
            case ltm_msgs_msg_SegmentChange_Constants_NEW:
                to = &out.added;
                ++out.added_segments;
                break;
            default:
                break;
        }
        if (!to || c.voxels._length % 3 != 0) {
            ++out.malformed;
            continue;
        }
        const bool vanished = c.reason == ltm_msgs_msg_SegmentChange_Constants_VANISHED;
        if (vanished) out.vanished.emplace_back();
        for (std::uint32_t k = 0; k + 2 < c.voxels._length; k += 3) {
            const Eigen::Vector3f p(c.voxels._buffer[k], c.voxels._buffer[k + 1],
                                    c.voxels._buffer[k + 2]);
            if (!p.allFinite()) continue;
            to->push_back(p);
            if (vanished) out.vanished.back().push_back(p);
        }
    }
    return out;
}

}  // namespace ltm::mapping
