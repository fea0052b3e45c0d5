// The only translation unit of ltm_common that includes PCL (its headers are slow to compile).
#include "common/core/pcl_cloud_io.hpp"

#include <pcl/PCLPointCloud2.h>
#include <pcl/console/print.h>
#include <pcl/io/pcd_io.h>
#include <pcl/io/ply_io.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "common/core/io_error.hpp"
#include "common/core/point_layout.hpp"

namespace ltm::common {
namespace {

std::string lower_extension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    return ext;
}

// PCL 1.13's PCDReader crashes on some malformed headers (seen: a text file without FIELDS), so
// the header is checked here first: every key PCL needs, sane counts, and enough bytes of data.
void check_pcd_header(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw IoError(path, "cannot open");
    std::map<std::string, std::vector<std::string>> keys;
    std::string line;
    std::size_t header_bytes = 0;
    for (int lineno = 1; lineno <= 64 && std::getline(in, line); ++lineno) {
        header_bytes += line.size() + 1;
        if (line.empty() || line[0] == '#') continue;
        std::istringstream ss(line);
        std::string key, v;
        ss >> key;
        if (key != "VERSION" && key != "FIELDS" && key != "SIZE" && key != "TYPE" && key != "COUNT" &&
            key != "WIDTH" && key != "HEIGHT" && key != "VIEWPOINT" && key != "POINTS" && key != "DATA")
            throw IoError(path, "not a PCD file: unexpected '" + key.substr(0, 32) + "' on header line " +
                                    std::to_string(lineno));
        while (ss >> v) keys[key].push_back(v);
        if (key == "DATA") break;
    }
    for (const char* k : {"FIELDS", "SIZE", "TYPE", "WIDTH", "POINTS", "DATA"})
        if (keys[k].empty()) throw IoError(path, std::string("PCD header has no ") + k + " line");
    const std::size_t nf = keys["FIELDS"].size();
    if (keys["SIZE"].size() != nf || keys["TYPE"].size() != nf ||
        (!keys["COUNT"].empty() && keys["COUNT"].size() != nf))
        throw IoError(path, "PCD header: FIELDS, SIZE, TYPE and COUNT differ in length");
    std::size_t step = 0;
    for (std::size_t i = 0; i < nf; ++i) {
        const long size = std::atol(keys["SIZE"][i].c_str());
        const long count = keys["COUNT"].empty() ? 1 : std::atol(keys["COUNT"][i].c_str());
        if (size != 1 && size != 2 && size != 4 && size != 8) throw IoError(path, "PCD header: bad SIZE");
        if (count < 1) throw IoError(path, "PCD header: bad COUNT");
        step += static_cast<std::size_t>(size * count);
    }
    const long points = std::atol(keys["POINTS"][0].c_str());
    if (points < 0) throw IoError(path, "PCD header: bad POINTS");
    if (keys["DATA"][0] == "binary") {
        const auto file_size = std::filesystem::file_size(path);
        const std::size_t need = header_bytes + static_cast<std::size_t>(points) * step;
        if (file_size < need)
            throw IoError(path, "truncated: " + std::to_string(file_size) + " bytes, header says " +
                                    std::to_string(need));
    } else if (keys["DATA"][0] != "ascii" && keys["DATA"][0] != "binary_compressed") {
        throw IoError(path, "PCD header: unknown DATA '" + keys["DATA"][0] + "'");
    }
}

}  // namespace

bool is_cloud_file(const std::string& path) {
    const std::string ext = lower_extension(path);
    return ext == ".pcd" || ext == ".ply";
}

PointCloud load_cloud_file(const std::string& path) {
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
    if (blob.data.size() < n * blob.point_step) throw IoError(path, "point data shorter than its header says");
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
        if (!fx[0] || !fx[1] || !fx[2]) throw IoError(path, "no x y z fields");
        for (std::size_t i = 0; i < n; ++i)
            for (int k = 0; k < 3; ++k) {
                double d;
                std::memcpy(&d, blob.data.data() + i * blob.point_step + fx[k]->offset, 8);
                const float v = static_cast<float>(d);
                std::memcpy(packed.data() + i * l2.point_step + 4 * k, &v, 4);
            }
        const std::string err = decode_points(l2, packed.data(), n, 0.0, cloud);
        if (!err.empty()) throw IoError(path, err);
        cloud.intensity.clear();
        return cloud;
    }
    const std::string err = decode_points(layout, blob.data.data(), n, 0.0, cloud);
    if (!err.empty()) throw IoError(path, err);
    return cloud;
}

}  // namespace ltm::common
