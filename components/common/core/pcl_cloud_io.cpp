// The only translation unit of ltm_common that includes PCL (its headers are slow to compile).
#include "common/core/pcl_cloud_io.hpp"

#include <pcl/PCLPointCloud2.h>
#include <pcl/console/print.h>
#include <pcl/io/pcd_io.h>
#include <pcl/io/ply_io.h>

#include <algorithm>
#include <cstring>
#include <filesystem>

#include "common/core/cloud_header_check.hpp"
#include "common/core/io_error.hpp"
#include "common/core/point_layout.hpp"

namespace ltm::common {
namespace {

std::string lower_extension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return std::tolower(c); });
    return ext;
}

}  // namespace

bool is_cloud_file(const std::string& path) {
    const std::string ext = lower_extension(path);
    return ext == ".pcd" || ext == ".ply";
}

PointCloud load_cloud_file(const std::string& path, double stamp) {
    if (!std::filesystem::is_regular_file(path)) throw IoError(path, "no such file");
    const std::string ext = lower_extension(path);
    // Our own one-line IoError replaces PCL's console chatter.
    pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
    pcl::PCLPointCloud2 blob;
    int rc = -1;
    if (ext == ".pcd") {
        check_pcd_header(path);
        pcl::PCDReader reader;
        rc = reader.read(path, blob);
    } else if (ext == ".ply") {
        check_ply_header(path);
        pcl::PLYReader reader;
        rc = reader.read(path, blob);
    } else {
        throw IoError(path, "unknown extension '" + ext + "' (expected .pcd or .ply)");
    }
    if (rc < 0) throw IoError(path, "PCL could not parse the file (malformed " + ext + ")");

    PointLayout layout;
    layout.point_step = blob.point_step;
    layout.big_endian = blob.is_bigendian;
    for (const auto& f : blob.fields) {
        PointField pf{f.name, f.offset, f.datatype, f.count};
        // PLY files often name intensity differently.
        if (pf.name == "scalar_intensity" || pf.name == "scalar_Intensity" || pf.name == "i")
            pf.name = "intensity";
        layout.fields.push_back(pf);
    }
    // Accept float64 coordinates (some PLY writers) by converting them first.
    const std::size_t n = static_cast<std::size_t>(blob.width) * blob.height;
    if (blob.data.size() < n * blob.point_step)
        throw IoError(path, "point data shorter than its header says");
    bool doubles = false;
    for (const auto& f : layout.fields)
        if ((f.name == "x" || f.name == "y" || f.name == "z") && f.datatype == 8) doubles = true;
    PointCloud cloud;
    if (doubles) {
        PointLayout l2 = standard_layout(false);
        std::vector<std::uint8_t> packed(n * l2.point_step, 0);
        auto off = [&](const char* name) -> const PointField* {
            for (const auto& f : layout.fields)
                if (f.name == name) return &f;
            return nullptr;
        };
        const PointField* fx[3] = {off("x"), off("y"), off("z")};
        if (layout.big_endian) throw IoError(path, "big-endian point data is not supported");
        for (const PointField* f : fx) {  // each coordinate float32 or float64, inside the point
            if (!f) throw IoError(path, "no x y z fields");
            if (f->datatype != 7 && f->datatype != 8)
                throw IoError(path, "field '" + f->name + "' is datatype " +
                                        std::to_string(f->datatype) +
                                        ", need float32 (7) or float64 (8)");
            if (f->offset + std::size_t{f->datatype == 8 ? 8u : 4u} > blob.point_step)
                throw IoError(path, "field '" + f->name + "' does not fit in point_step " +
                                        std::to_string(blob.point_step));
        }
        for (std::size_t i = 0; i < n; ++i)
            for (int k = 0; k < 3; ++k) {
                const std::uint8_t* p = blob.data.data() + i * blob.point_step + fx[k]->offset;
                float v;
                if (fx[k]->datatype == 8) {
                    double d;
                    std::memcpy(&d, p, 8);
                    v = static_cast<float>(d);
                } else {
                    std::memcpy(&v, p, 4);
                }
                std::memcpy(packed.data() + i * l2.point_step + 4 * k, &v, 4);
            }
        const std::string err = decode_points(l2, packed.data(), n, stamp, cloud);
        if (!err.empty()) throw IoError(path, err);
        cloud.intensity.clear();
        return cloud;
    }
    const std::string err = decode_points(layout, blob.data.data(), n, stamp, cloud);
    if (!err.empty()) throw IoError(path, err);
    return cloud;
}

}  // namespace ltm::common
