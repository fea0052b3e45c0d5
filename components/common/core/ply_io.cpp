#include "common/core/ply_io.hpp"

#include <cstdio>
#include <cstring>
#include <filesystem>

#include "common/core/io_error.hpp"

namespace ltm::common {
namespace {

class AtomicFile {
  public:
    explicit AtomicFile(const std::string& path) : path_(path), tmp_(path + ".tmp") {
        f_ = std::fopen(tmp_.c_str(), "wb");
        if (!f_) throw IoError(path, "cannot open for writing");
    }
    ~AtomicFile() {
        if (f_) {
            std::fclose(f_);
            std::remove(tmp_.c_str());
        }
    }
    void write(const void* data, std::size_t bytes) {
        if (bytes && std::fwrite(data, 1, bytes, f_) != bytes) throw IoError(path_, "write failed");
    }
    void write(const std::string& s) { write(s.data(), s.size()); }
    void commit() {
        const bool ok = std::fflush(f_) == 0;
        std::fclose(f_);
        f_ = nullptr;
        if (!ok) throw IoError(path_, "write failed");
        std::error_code ec;
        std::filesystem::rename(tmp_, path_, ec);
        if (ec) throw IoError(path_, "rename failed: " + ec.message());
    }

  private:
    std::string path_, tmp_;
    std::FILE* f_ = nullptr;
};

}  // namespace

void write_ply(const std::string& path, const PlyCloud& cloud) {
    const std::size_t n = cloud.points.size();
    const bool has_n = !cloud.normals.empty(), has_i = !cloud.intensity.empty();
    if ((has_n && cloud.normals.size() != n) || (has_i && cloud.intensity.size() != n))
        throw IoError(path, "point channels differ in size");
    std::string header =
        "ply\nformat binary_little_endian 1.0\ncomment written by ltm\nelement vertex " +
        std::to_string(n) + "\nproperty float x\nproperty float y\nproperty float z\n";
    if (has_n) header += "property float nx\nproperty float ny\nproperty float nz\n";
    if (has_i) header += "property float intensity\n";
    header += "end_header\n";
    std::vector<float> row;
    row.reserve(n * 7);
    for (std::size_t i = 0; i < n; ++i) {
        row.insert(row.end(), cloud.points[i].data(), cloud.points[i].data() + 3);
        if (has_n) row.insert(row.end(), cloud.normals[i].data(), cloud.normals[i].data() + 3);
        if (has_i) row.push_back(cloud.intensity[i]);
    }
    AtomicFile f(path);
    f.write(header);
    f.write(row.data(), row.size() * sizeof(float));
    f.commit();
}

void write_ply(const std::string& path, const PlyMesh& mesh) {
    const std::size_t n = mesh.vertices.size();
    const bool has_n = !mesh.normals.empty();
    if (has_n && mesh.normals.size() != n)
        throw IoError(path, "normals differ in size from vertices");
    for (const auto& t : mesh.triangles)
        if ((t.array() < 0).any() || (t.array() >= static_cast<int>(n)).any())
            throw IoError(path, "triangle index out of range");
    std::string header =
        "ply\nformat binary_little_endian 1.0\ncomment written by ltm\nelement vertex " +
        std::to_string(n) + "\nproperty float x\nproperty float y\nproperty float z\n";
    if (has_n) header += "property float nx\nproperty float ny\nproperty float nz\n";
    header += "element face " + std::to_string(mesh.triangles.size()) +
              "\nproperty list uchar int vertex_indices\nend_header\n";
    std::vector<float> verts;
    verts.reserve(n * 6);
    for (std::size_t i = 0; i < n; ++i) {
        verts.insert(verts.end(), mesh.vertices[i].data(), mesh.vertices[i].data() + 3);
        if (has_n) verts.insert(verts.end(), mesh.normals[i].data(), mesh.normals[i].data() + 3);
    }
    std::vector<unsigned char> faces(mesh.triangles.size() * 13);
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
        faces[13 * i] = 3;
        const int idx[3] = {mesh.triangles[i][0], mesh.triangles[i][1], mesh.triangles[i][2]};
        std::memcpy(&faces[13 * i + 1], idx, 12);
    }
    AtomicFile f(path);
    f.write(header);
    f.write(verts.data(), verts.size() * sizeof(float));
    f.write(faces.data(), faces.size());
    f.commit();
}

}  // namespace ltm::common
