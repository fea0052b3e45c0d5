#pragma once
// sensor_msgs/PointCloud2 <-> common::PointCloud. Any layout with float32 x y z, optional
// intensity and an optional per-point time (t, time, timestamp, offset_time) is accepted.
#include <string>
#include <vector>

#include "common/core/point_cloud.hpp"
#include "common/core/point_layout.hpp"
#include "runtime/messages.hpp"

namespace ltm::convert {

// Returns "" on success, else a one-line reason (unsupported layout, inconsistent sizes).
std::string from_pointcloud2(const msg::PointCloud2& message, common::PointCloud& out);

// Builds PointCloud2 messages over buffers it owns (borrowed, see dds_string.hpp: never pass the
// message to a free function); the message stays valid until the next build().
class PointCloud2Builder {
  public:
    const msg::PointCloud2& build(const common::PointCloud& cloud);

  private:
    std::vector<std::uint8_t> data_;
    common::PointLayout layout_;
    std::vector<msg::PointField> fields_;
    std::string frame_id_;
    msg::PointCloud2 message_{};
};

}  // namespace ltm::convert
