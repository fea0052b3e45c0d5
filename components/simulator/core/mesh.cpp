#include "simulator/core/mesh.hpp"

#include <array>
#include <cmath>
#include <map>
#include <utility>

namespace ltm::sim {
namespace {

struct UnitSphere {
    std::vector<Eigen::Vector3d> vertices;
    std::vector<Eigen::Vector3i> faces;
};

// Icosahedron subdivided once: 42 vertices, 80 faces.
UnitSphere make_icosphere() {
    const double t = (1.0 + std::sqrt(5.0)) / 2.0;
    UnitSphere s;
    s.vertices = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                  {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
    for (auto& v : s.vertices) v.normalize();
    const std::vector<Eigen::Vector3i> base = {
        {0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
        {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
        {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
    std::map<std::pair<int, int>, int> midpoints;
    auto mid = [&](int a, int b) {
        const auto key = std::minmax(a, b);
        const auto it = midpoints.find(key);
        if (it != midpoints.end()) return it->second;
        s.vertices.push_back((s.vertices[a] + s.vertices[b]).normalized());
        const int id = static_cast<int>(s.vertices.size()) - 1;
        midpoints.emplace(key, id);
        return id;
    };
    for (const auto& f : base) {
        const int ab = mid(f[0], f[1]), bc = mid(f[1], f[2]), ca = mid(f[2], f[0]);
        s.faces.push_back({f[0], ab, ca});
        s.faces.push_back({f[1], bc, ab});
        s.faces.push_back({f[2], ca, bc});
        s.faces.push_back({ab, bc, ca});
    }
    return s;
}

}  // namespace

void Mesh::append(const Mesh& other) {
    const int offset = static_cast<int>(vertices.size());
    vertices.insert(vertices.end(), other.vertices.begin(), other.vertices.end());
    for (const auto& t : other.triangles)
        triangles.push_back(t + Eigen::Vector3i::Constant(offset));
    material.insert(material.end(), other.material.begin(), other.material.end());
    object.insert(object.end(), other.object.begin(), other.object.end());
}

Eigen::AlignedBox3f Mesh::bounds() const {
    Eigen::AlignedBox3f box;
    for (const auto& v : vertices) box.extend(v);
    return box;
}

int MeshBuilder::vertex(const Eigen::Vector3d& p_local) {
    mesh_.vertices.push_back((T_ * p_local).cast<float>());
    return static_cast<int>(mesh_.vertices.size()) - 1;
}

void MeshBuilder::face(int a, int b, int c) {
    mesh_.triangles.emplace_back(a, b, c);
    mesh_.material.push_back(material_);
    mesh_.object.push_back(object_);
}

void MeshBuilder::triangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                           const Eigen::Vector3d& c) {
    face(vertex(a), vertex(b), vertex(c));
}

void MeshBuilder::quad(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                       const Eigen::Vector3d& d) {
    const int ia = vertex(a), ib = vertex(b), ic = vertex(c), id = vertex(d);
    face(ia, ib, ic);
    face(ia, ic, id);
}

void MeshBuilder::box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
    std::array<int, 8> v;
    for (int i = 0; i < 8; ++i) {
        v[i] = vertex(
            {(i & 1) ? hi.x() : lo.x(), (i & 2) ? hi.y() : lo.y(), (i & 4) ? hi.z() : lo.z()});
    }
    // Outward-facing quads: -z, +z, -y, +y, -x, +x.
    const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                             {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& q : quads) {
        face(v[q[0]], v[q[1]], v[q[2]]);
        face(v[q[0]], v[q[2]], v[q[3]]);
    }
}

void MeshBuilder::frustum(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double r0, double r1,
                          int segments, bool caps) {
    const Eigen::Vector3d axis = (b - a).normalized();
    const Eigen::Vector3d helper =
        std::abs(axis.z()) < 0.9 ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d::UnitX();
    const Eigen::Vector3d u = axis.cross(helper).normalized();
    const Eigen::Vector3d w = axis.cross(u);
    const int base = static_cast<int>(mesh_.vertices.size());
    for (int i = 0; i < segments; ++i) {
        const double phi = 2.0 * M_PI * i / segments;
        const Eigen::Vector3d dir = std::cos(phi) * u + std::sin(phi) * w;
        vertex(a + r0 * dir);
        vertex(b + r1 * dir);
    }
    for (int i = 0; i < segments; ++i) {
        const int j = (i + 1) % segments;
        const int a0 = base + 2 * i, b0 = a0 + 1, a1 = base + 2 * j, b1 = a1 + 1;
        face(a0, a1, b1);
        face(a0, b1, b0);
    }
    if (!caps) return;
    const int ca = vertex(a), cb = vertex(b);
    for (int i = 0; i < segments; ++i) {
        const int j = (i + 1) % segments;
        if (r0 > 0) face(ca, base + 2 * j, base + 2 * i);
        if (r1 > 0) face(cb, base + 2 * i + 1, base + 2 * j + 1);
    }
}

void MeshBuilder::ellipsoid(const Eigen::Vector3d& center, const Eigen::Vector3d& radii) {
    static const UnitSphere sphere = make_icosphere();
    const int base = static_cast<int>(mesh_.vertices.size());
    for (const auto& v : sphere.vertices) vertex(center + v.cwiseProduct(radii));
    for (const auto& f : sphere.faces) face(base + f[0], base + f[1], base + f[2]);
}

void MeshBuilder::gable_roof(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
    const double ym = 0.5 * (lo.y() + hi.y());
    const Eigen::Vector3d p0(lo.x(), lo.y(), lo.z()), p1(hi.x(), lo.y(), lo.z());
    const Eigen::Vector3d p2(hi.x(), hi.y(), lo.z()), p3(lo.x(), hi.y(), lo.z());
    const Eigen::Vector3d r0(lo.x(), ym, hi.z()), r1(hi.x(), ym, hi.z());
    quad(p0, p1, r1, r0);  // south slope
    quad(p2, p3, r0, r1);  // north slope
    triangle(p0, r0, p3);  // gable ends
    triangle(p1, p2, r1);
}

Eigen::Isometry3d ground_pose(double x, double y, double z, double yaw) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    T.translation() = Eigen::Vector3d(x, y, z);
    return T;
}

}  // namespace ltm::sim
