#pragma once
// Packed point layouts as PointCloud2 and PCD describe them: named fields at byte offsets.
// Decoding accepts float32 x y z, optional intensity and an optional per-point time field
// (t, time, timestamp, offset_time); anything else gets a one-line reason.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "common/core/point_cloud.hpp"

namespace ltm::common {

// Data types, numbered as sensor_msgs/PointField.
enum class FieldType : std::uint8_t {
    kInt8 = 1,
    kUInt8 = 2,
    kInt16 = 3,
    kUInt16 = 4,
    kInt32 = 5,
    kUInt32 = 6,
    kFloat32 = 7,
    kFloat64 = 8
};
std::size_t field_type_size(std::uint8_t datatype);  // 0 for an unknown type

struct PointField {
    std::string name;
    std::uint32_t offset = 0;
    std::uint8_t datatype = 0;
    std::uint32_t count = 1;
};

struct PointLayout {
    std::vector<PointField> fields;
    std::uint32_t point_step = 0;
    bool big_endian = false;
};

// Decodes `n` points of `layout` from `data` (n * point_step bytes; rows may be padded with
// row_step, give the bytes of each row contiguously). Point times become seconds after `stamp`:
// integer time fields are nanoseconds, float fields seconds; absolute times (> 1e6 s) are made
// relative to `stamp`. Returns an empty string on success, else the reason. Non-finite points are
// kept; call remove_non_finite().
std::string decode_points(const PointLayout& layout, const std::uint8_t* data, std::size_t n,
                          double stamp, PointCloud& out);

// The layout ltm publishes: x y z intensity float32, plus float32 `t` (s) when the cloud has times.
PointLayout standard_layout(bool with_time);
void encode_points(const PointCloud& cloud, const PointLayout& layout,
                   std::vector<std::uint8_t>& data);

}  // namespace ltm::common
