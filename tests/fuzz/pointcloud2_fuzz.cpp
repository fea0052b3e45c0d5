// Fuzz target: sensor_msgs/PointCloud2 -> common::PointCloud (runtime/convert/pointcloud2), the
// conversion every LiDAR message from the network goes through. The message is built from the
// input (Cyclone has already checked the CDR framing; the fields' meaning is ours to check):
//   u32 width, u32 height, u32 point_step, u32 row_step, u8 is_bigendian, u8 field count (% 9),
//   per field: u8 name (index into kNames), u32 offset, u8 datatype, u32 count;
//   then u32 sec, u32 nanosec and the rest is `data` (all little-endian).
// Promise: "" and a consistent cloud of width * height points, or a one-line reason.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

#include "fuzz_util.hpp"
#include "runtime/convert/pointcloud2.hpp"

namespace {

const char* const kNames[] = {"x",         "y",           "z",   "intensity", "t", "time",
                              "timestamp", "offset_time", "rgb", "i",         ""};

struct Bytes {
    const std::uint8_t* p;
    std::size_t n;
    template <class T>
    T take() {
        T v{};
        const std::size_t k = n < sizeof(T) ? n : sizeof(T);
        std::memcpy(&v, p, k);
        p += k;
        n -= k;
        return v;
    }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    Bytes in{data, size};
    ltm::msg::PointCloud2 m{};
    m.width = in.take<std::uint32_t>();
    m.height = in.take<std::uint32_t>();
    m.point_step = in.take<std::uint32_t>();
    m.row_step = in.take<std::uint32_t>();
    m.is_bigendian = in.take<std::uint8_t>() & 1;
    std::vector<ltm::msg::PointField> fields(in.take<std::uint8_t>() % 9);
    for (auto& f : fields) {
        f.name =
            const_cast<char*>(kNames[in.take<std::uint8_t>() % (sizeof kNames / sizeof *kNames)]);
        f.offset = in.take<std::uint32_t>();
        f.datatype = in.take<std::uint8_t>();
        f.count = in.take<std::uint32_t>();
    }
    m.header.stamp.sec = in.take<std::int32_t>();
    m.header.stamp.nanosec = in.take<std::uint32_t>();
    char frame[] = "lidar";
    m.header.frame_id = frame;
    // The payload in a buffer of its own size, so that reading past it is caught.
    std::vector<std::uint8_t> payload(in.p, in.p + in.n);
    m.fields._buffer = fields.data();
    m.fields._length = m.fields._maximum = static_cast<std::uint32_t>(fields.size());
    m.data._buffer = payload.data();
    m.data._length = m.data._maximum = static_cast<std::uint32_t>(payload.size());

    ltm::common::PointCloud cloud;
    const std::string err = ltm::convert::from_pointcloud2(m, cloud);
    if (!err.empty()) {
        if (err.find('\n') != std::string::npos)
            ltm::fuzz::finding("a reason of more than one line: " + err);
        return 0;
    }
    if (cloud.size() != static_cast<std::size_t>(m.width) * m.height || !cloud.consistent())
        ltm::fuzz::finding("a cloud of " + std::to_string(cloud.size()) + " points from " +
                           std::to_string(m.width) + " x " + std::to_string(m.height));
    return 0;
}
