// The only file of the evaluation that includes PCL (slow headers).
#include "evaluation/core/mesh_io.hpp"

#include <pcl/PolygonMesh.h>
#include <pcl/conversions.h>
#include <pcl/io/ply_io.h>
#include <pcl/point_types.h>

#include <filesystem>

#include "common/core/io_error.hpp"

namespace ltm::eval {

namespace {

pcl::PolygonMesh load_ply(const std::string& path) {
    if (!std::filesystem::is_regular_file(path)) throw common::IoError(path, "no such file");
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (ext != ".ply") throw common::IoError(path, "meshes are read from .ply files only");

    pcl::PolygonMesh mesh;
    if (pcl::io::loadPLYFile(path, mesh) < 0)
        throw common::IoError(path, "not a readable PLY file");
    bool has_xyz = false;
    for (const auto& f : mesh.cloud.fields) has_xyz |= f.name == "x";
    if (!has_xyz) throw common::IoError(path, "PLY vertices have no x y z");
    return mesh;
}

}  // namespace

ColouredCloud read_coloured_cloud(const std::string& path) {
    const pcl::PolygonMesh mesh = load_ply(path);
    bool has_rgb = false;
    for (const auto& f : mesh.cloud.fields) has_rgb |= f.name == "rgb" || f.name == "red";
    ColouredCloud out;
    if (has_rgb) {
        pcl::PointCloud<pcl::PointXYZRGB> cloud;
        pcl::fromPCLPointCloud2(mesh.cloud, cloud);
        out.points.reserve(cloud.size());
        out.colours.reserve(cloud.size());
        for (const auto& p : cloud.points) {
            out.points.emplace_back(p.x, p.y, p.z);
            out.colours.push_back({p.r, p.g, p.b});
        }
        return out;
    }
    pcl::PointCloud<pcl::PointXYZ> cloud;
    pcl::fromPCLPointCloud2(mesh.cloud, cloud);
    out.points.reserve(cloud.size());
    for (const auto& p : cloud.points) out.points.emplace_back(p.x, p.y, p.z);
    return out;
}

common::PlyMesh read_mesh_file(const std::string& path) {
    const pcl::PolygonMesh mesh = load_ply(path);
    pcl::PointCloud<pcl::PointXYZ> cloud;
    pcl::fromPCLPointCloud2(mesh.cloud, cloud);

    common::PlyMesh out;
    out.vertices.reserve(cloud.size());
    for (const auto& p : cloud.points) out.vertices.emplace_back(p.x, p.y, p.z);
    const auto n = static_cast<std::int64_t>(out.vertices.size());
    for (const auto& poly : mesh.polygons) {
        const auto& v = poly.vertices;
        for (std::size_t k = 2; k < v.size(); ++k) {
            const Eigen::Vector3i t(static_cast<int>(v[0]), static_cast<int>(v[k - 1]),
                                    static_cast<int>(v[k]));
            if (t.minCoeff() < 0 || t.maxCoeff() >= n)
                throw common::IoError(path, "a face names vertex " + std::to_string(t.maxCoeff()) +
                                                " of " + std::to_string(n));
            out.triangles.push_back(t);
        }
    }
    return out;
}

}  // namespace ltm::eval
