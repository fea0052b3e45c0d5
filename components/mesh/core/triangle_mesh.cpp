#include "mesh/core/triangle_mesh.hpp"

namespace ltm::mesh {

namespace {

bool valid(const common::PlyMesh& mesh, const Eigen::Vector3i& t) {
    const int n = int(mesh.vertices.size());
    return t.minCoeff() >= 0 && t.maxCoeff() < n;
}

}  // namespace

std::vector<Eigen::Vector3f> vertex_normals(const common::PlyMesh& mesh) {
    std::vector<Eigen::Vector3f> normals(mesh.vertices.size(), Eigen::Vector3f::Zero());
    for (const Eigen::Vector3i& t : mesh.triangles) {
        if (!valid(mesh, t)) continue;
        const Eigen::Vector3f& a = mesh.vertices[t[0]];
        const Eigen::Vector3f n = (mesh.vertices[t[1]] - a).cross(mesh.vertices[t[2]] - a);
        for (int k = 0; k < 3; ++k) normals[t[k]] += n;  // |n| = twice the area: area-weighted
    }
    for (Eigen::Vector3f& n : normals) {
        const float len = n.norm();
        n = len > 0.0f ? Eigen::Vector3f(n / len) : Eigen::Vector3f::Zero();
    }
    return normals;
}

common::PlyMesh transformed(const common::PlyMesh& mesh, const Eigen::Isometry3d& T) {
    common::PlyMesh out;
    append(out, mesh, T);
    return out;
}

void append(common::PlyMesh& into, const common::PlyMesh& part, const Eigen::Isometry3d& T) {
    const Eigen::Isometry3f Tf = T.cast<float>();
    const Eigen::Matrix3f R = Tf.linear();
    const bool normals = (into.vertices.empty() || into.normals.size() == into.vertices.size()) &&
                         part.normals.size() == part.vertices.size();
    if (!normals) into.normals.clear();
    const int offset = int(into.vertices.size());
    into.vertices.reserve(into.vertices.size() + part.vertices.size());
    for (const Eigen::Vector3f& v : part.vertices) into.vertices.push_back(Tf * v);
    if (normals)
        for (const Eigen::Vector3f& n : part.normals) into.normals.push_back(R * n);
    into.triangles.reserve(into.triangles.size() + part.triangles.size());
    for (const Eigen::Vector3i& t : part.triangles)
        if (valid(part, t)) into.triangles.push_back(t.array() + offset);
}

common::PlyMesh sub_mesh(const common::PlyMesh& mesh, const std::vector<std::uint8_t>& keep) {
    common::PlyMesh out;
    const bool normals = mesh.normals.size() == mesh.vertices.size();
    std::vector<int> remap(mesh.vertices.size(), -1);
    for (std::size_t i = 0; i < mesh.triangles.size() && i < keep.size(); ++i) {
        const Eigen::Vector3i& t = mesh.triangles[i];
        if (!keep[i] || !valid(mesh, t)) continue;
        Eigen::Vector3i u;
        for (int k = 0; k < 3; ++k) {
            int& r = remap[t[k]];
            if (r < 0) {
                r = int(out.vertices.size());
                out.vertices.push_back(mesh.vertices[t[k]]);
                if (normals) out.normals.push_back(mesh.normals[t[k]]);
            }
            u[k] = r;
        }
        out.triangles.push_back(u);
    }
    return out;
}

double surface_area(const common::PlyMesh& mesh) {
    double area = 0.0;
    for (const Eigen::Vector3i& t : mesh.triangles) {
        if (!valid(mesh, t)) continue;
        const Eigen::Vector3d a = mesh.vertices[t[0]].cast<double>();
        const Eigen::Vector3d b = mesh.vertices[t[1]].cast<double>();
        const Eigen::Vector3d c = mesh.vertices[t[2]].cast<double>();
        area += 0.5 * (b - a).cross(c - a).norm();
    }
    return area;
}

Eigen::Vector3f centroid(const common::PlyMesh& mesh, std::size_t t) {
    const Eigen::Vector3i& i = mesh.triangles[t];
    return (mesh.vertices[i[0]] + mesh.vertices[i[1]] + mesh.vertices[i[2]]) / 3.0f;
}

}  // namespace ltm::mesh
