#pragma once
// ltm_msgs/LocalMap and ltm_msgs/Keyframe <-> common::LocalMapData / KeyframeData.
#include <string>
#include <vector>

#include "common/core/local_map_data.hpp"
#include "runtime/convert/pointcloud2.hpp"
#include "runtime/messages.hpp"

namespace ltm::convert {

common::LocalMapData from_msg(const msg::LocalMap& m);
common::KeyframeData from_msg(const msg::Keyframe& m);

// Builds a LocalMap message over buffers it owns and the map's own vectors (borrowed, see
// dds_string.hpp: never pass it to a free function); valid until the next build() and while `map`
// lives unchanged.
class LocalMapBuilder {
  public:
    const msg::LocalMap& build(const common::LocalMapData& map, double stamp,
                               const std::string& frame_id);

  private:
    std::vector<msg::Voxel> voxels_;
    std::string frame_id_;
    msg::LocalMap message_{};
};

// Builds a Keyframe message (points as PointCloud2, without descriptors: rings 0; an unknown
// segment as 0).
class KeyframeBuilder {
  public:
    const msg::Keyframe& build(const common::KeyframeData& keyframe, const std::string& frame_id,
                               const std::string& lidar_frame_id);

  private:
    PointCloud2Builder points_;
    common::PointCloud cloud_;
    std::string frame_id_;
    msg::Keyframe message_{};
};

}  // namespace ltm::convert
