#include "common/core/point_layout.hpp"

#include <cmath>
#include <cstring>

namespace ltm::common {
namespace {

const PointField* find_field(const PointLayout& layout, const char* name) {
    for (const auto& f : layout.fields)
        if (f.name == name) return &f;
    return nullptr;
}

double read_scalar(const std::uint8_t* p, std::uint8_t type) {
    switch (static_cast<FieldType>(type)) {
        case FieldType::kInt8: {
            std::int8_t v;
            std::memcpy(&v, p, 1);
            return v;
        }
        case FieldType::kUInt8:
            return *p;
        case FieldType::kInt16: {
            std::int16_t v;
            std::memcpy(&v, p, 2);
            return v;
        }
        case FieldType::kUInt16: {
            std::uint16_t v;
            std::memcpy(&v, p, 2);
            return v;
        }
        case FieldType::kInt32: {
            std::int32_t v;
            std::memcpy(&v, p, 4);
            return v;
        }
        case FieldType::kUInt32: {
            std::uint32_t v;
            std::memcpy(&v, p, 4);
            return v;
        }
        case FieldType::kFloat32: {
            float v;
            std::memcpy(&v, p, 4);
            return v;
        }
        case FieldType::kFloat64: {
            double v;
            std::memcpy(&v, p, 8);
            return v;
        }
    }
    return 0.0;
}

std::string check_field(const PointLayout& layout, const PointField& f) {
    const std::size_t size = field_type_size(f.datatype);
    if (size == 0)
        return "field '" + f.name + "' has unknown datatype " + std::to_string(f.datatype);
    if (f.count != 1)
        return "field '" + f.name + "' has count " + std::to_string(f.count) + " (need 1)";
    if (f.offset + size > layout.point_step)
        return "field '" + f.name + "' at offset " + std::to_string(f.offset) +
               " does not fit in point_step " + std::to_string(layout.point_step);
    return "";
}

}  // namespace

std::size_t field_type_size(std::uint8_t datatype) {
    switch (datatype) {
        case 1:
        case 2:
            return 1;
        case 3:
        case 4:
            return 2;
        case 5:
        case 6:
        case 7:
            return 4;
        case 8:
            return 8;
        default:
            return 0;
    }
}

std::string decode_points(const PointLayout& layout, const std::uint8_t* data, std::size_t n,
                          double stamp, PointCloud& out) {
    if (layout.big_endian) return "big-endian point data is not supported";
    if (layout.point_step == 0 && n > 0) return "point_step is 0";
    const PointField* xyz[3] = {find_field(layout, "x"), find_field(layout, "y"),
                                find_field(layout, "z")};
    for (int k = 0; k < 3; ++k) {
        const char* axis = k == 0 ? "x" : (k == 1 ? "y" : "z");
        if (!xyz[k]) return std::string("no '") + axis + "' field (need float32 x y z)";
        if (xyz[k]->datatype != static_cast<std::uint8_t>(FieldType::kFloat32))
            return std::string("field '") + axis + "' is datatype " +
                   std::to_string(xyz[k]->datatype) + ", need float32 (7)";
        if (auto e = check_field(layout, *xyz[k]); !e.empty()) return e;
    }
    const PointField* inten = find_field(layout, "intensity");
    if (inten)
        if (auto e = check_field(layout, *inten); !e.empty()) return e;
    const PointField* time = nullptr;
    for (const char* name : {"t", "time", "timestamp", "offset_time"})
        if ((time = find_field(layout, name))) break;
    if (time)
        if (auto e = check_field(layout, *time); !e.empty()) return e;

    out.clear();
    out.stamp = stamp;
    out.reserve(n, inten != nullptr, time != nullptr);
    const bool fast_xyz =
        xyz[1]->offset == xyz[0]->offset + 4 && xyz[2]->offset == xyz[0]->offset + 8;
    const bool time_is_float =
        time && (time->datatype == static_cast<std::uint8_t>(FieldType::kFloat32) ||
                 time->datatype == static_cast<std::uint8_t>(FieldType::kFloat64));
    for (std::size_t i = 0; i < n; ++i) {
        const std::uint8_t* p = data + i * layout.point_step;
        float v[3];
        if (fast_xyz) {
            std::memcpy(v, p + xyz[0]->offset, 12);
        } else {
            for (int k = 0; k < 3; ++k) std::memcpy(&v[k], p + xyz[k]->offset, 4);
        }
        out.points.emplace_back(v[0], v[1], v[2]);
        if (inten)
            out.intensity.push_back(
                static_cast<float>(read_scalar(p + inten->offset, inten->datatype)));
        if (time) {
            double t = read_scalar(p + time->offset, time->datatype);
            if (!time_is_float) t *= 1e-9;
            if (std::abs(t) > 1e6) t -= stamp;
            out.time.push_back(static_cast<float>(t));
        }
    }
    return "";
}

PointLayout standard_layout(bool with_time) {
    PointLayout layout;
    const auto f32 = static_cast<std::uint8_t>(FieldType::kFloat32);
    layout.fields = {
        {"x", 0, f32, 1}, {"y", 4, f32, 1}, {"z", 8, f32, 1}, {"intensity", 12, f32, 1}};
    if (with_time) layout.fields.push_back({"t", 16, f32, 1});
    layout.point_step = with_time ? 20 : 16;
    return layout;
}

void encode_points(const PointCloud& cloud, const PointLayout& layout,
                   std::vector<std::uint8_t>& data) {
    const std::size_t n = cloud.size();
    const std::size_t step = layout.point_step;
    data.assign(n * step, 0);
    const bool with_time = step >= 20 && cloud.has_time();
    for (std::size_t i = 0; i < n; ++i) {
        std::uint8_t* p = data.data() + i * step;
        std::memcpy(p, cloud.points[i].data(), 12);
        const float inten = cloud.has_intensity() ? cloud.intensity[i] : 0.0f;
        std::memcpy(p + 12, &inten, 4);
        if (with_time) std::memcpy(p + 16, &cloud.time[i], 4);
    }
}

}  // namespace ltm::common
