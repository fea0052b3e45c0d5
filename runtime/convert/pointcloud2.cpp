#include "runtime/convert/pointcloud2.hpp"

#include "runtime/convert/dds_string.hpp"
#include "runtime/convert/geometry.hpp"

namespace ltm::convert {

std::string from_pointcloud2(const msg::PointCloud2& m, common::PointCloud& out) {
    common::PointLayout layout;
    layout.point_step = m.point_step;
    layout.big_endian = m.is_bigendian;
    for (std::uint32_t i = 0; i < m.fields._length; ++i) {
        const msg::PointField& f = m.fields._buffer[i];
        layout.fields.push_back({f.name ? f.name : "", f.offset, f.datatype, f.count});
    }
    const std::size_t width = m.width, height = m.height;
    if (height > 0 && m.row_step < width * m.point_step)
        return "row_step " + std::to_string(m.row_step) + " is smaller than width * point_step";
    if (m.data._length < height * static_cast<std::size_t>(m.row_step))
        return "data holds " + std::to_string(m.data._length) + " bytes, height * row_step says " +
               std::to_string(height * static_cast<std::size_t>(m.row_step));
    const double stamp = to_seconds(m.header.stamp);
    if (m.row_step == width * m.point_step || height <= 1) {
        const std::string err =
            common::decode_points(layout, m.data._buffer, width * height, stamp, out);
        out.frame_id = m.header.frame_id ? m.header.frame_id : "";
        return err;
    }
    // Padded rows: decode row by row.
    common::PointCloud row;
    out.clear();
    for (std::size_t r = 0; r < height; ++r) {
        const std::string err =
            common::decode_points(layout, m.data._buffer + r * m.row_step, width, stamp, row);
        if (!err.empty()) return err;
        out.points.insert(out.points.end(), row.points.begin(), row.points.end());
        out.intensity.insert(out.intensity.end(), row.intensity.begin(), row.intensity.end());
        out.time.insert(out.time.end(), row.time.begin(), row.time.end());
    }
    out.stamp = stamp;
    out.frame_id = m.header.frame_id ? m.header.frame_id : "";
    return "";
}

const msg::PointCloud2& PointCloud2Builder::build(const common::PointCloud& cloud) {
    layout_ = common::standard_layout(cloud.has_time());
    common::encode_points(cloud, layout_, data_);
    fields_.resize(layout_.fields.size());
    for (std::size_t i = 0; i < fields_.size(); ++i) {
        auto& f = layout_.fields[i];
        fields_[i].name = borrow_string(f.name);
        fields_[i].offset = f.offset;
        fields_[i].datatype = f.datatype;
        fields_[i].count = f.count;
    }
    frame_id_ = cloud.frame_id;
    message_ = msg::PointCloud2{};
    message_.header.stamp = to_time(cloud.stamp);
    message_.header.frame_id = borrow_string(frame_id_);
    message_.height = 1;
    message_.width = static_cast<std::uint32_t>(cloud.size());
    borrow_sequence(message_.fields, fields_);
    message_.is_bigendian = false;
    message_.point_step = layout_.point_step;
    message_.row_step = layout_.point_step * message_.width;
    borrow_sequence(message_.data, data_);
    message_.is_dense = true;
    return message_;
}

}  // namespace ltm::convert
