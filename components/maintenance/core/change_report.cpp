#include "maintenance/core/change_report.hpp"

#include <cstdio>
#include <cstring>

#include "common/core/file_io.hpp"
#include "maintenance/core/change_record.hpp"

namespace ltm::maintenance {

void write_change_summary(std::ostream& out, const ChangeSet& c, std::size_t pass) {
    char line[320];
    std::snprintf(line, sizeof line,
                  "session %u pass %zu at %.1f s: %zu moving, %zu vanished, %zu new segments; %zu "
                  "of %zu voxels removed, %zu judged, %zu segments, %zu ground; %.1f ms\n",
                  c.session, pass, c.map_time, c.count(ChangeReason::kMoving),
                  c.count(ChangeReason::kVanished), c.count(ChangeReason::kNew), c.voxels_removed,
                  c.voxels_before, c.voxels_judged, c.segments, c.ground_voxels, c.time_ms);
    out << line;
    for (const SegmentChange& s : c.changes) {
        const Eigen::Vector3f size = s.bbox_max - s.bbox_min;
        std::snprintf(line, sizeof line,
                      "  %-8s id %llu  centre %.2f %.2f %.2f  size %.1f x %.1f x %.1f  voxels %zu  "
                      "score %.2f  seen %.1f-%.1f s\n",
                      reason_name(s.reason), static_cast<unsigned long long>(s.id), s.centroid.x(),
                      s.centroid.y(), s.centroid.z(), size.x(), size.y(), size.z(), s.voxels.size(),
                      s.score, s.first_seen, s.last_seen);
        out << line;
    }
}

namespace {

// The PLY's vertices of `changes` appended to `body` (15 bytes a voxel).
void append_vertices(const ChangeSet& changes, std::string& body) {
    for (const SegmentChange& s : changes.changes) {
        const unsigned char rgb[3] = {static_cast<unsigned char>(s.removed() ? 220 : 30),
                                      static_cast<unsigned char>(s.removed() ? 30 : 200), 30};
        for (const Eigen::Vector3f& p : s.voxels) {
            char v[15];
            std::memcpy(v, p.data(), 12);
            std::memcpy(v + 12, rgb, 3);
            body.append(v, 15);
        }
    }
}

void write_ply(const std::string& path, const std::string& body) {
    const std::string header =
        "ply\nformat binary_little_endian 1.0\ncomment ltm map changes: removed red, added "
        "green\nelement vertex " +
        std::to_string(body.size() / 15) +
        "\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\n"
        "property uchar green\nproperty uchar blue\nend_header\n";
    common::write_file_atomic(path, header + body);
}

}  // namespace

void write_change_ply(const std::string& path, const ChangeSet& changes) {
    std::string body;
    append_vertices(changes, body);
    write_ply(path, body);
}

void write_change_ply(const std::string& path, const std::vector<std::string>& records) {
    std::string body;
    for (const std::string& r : records) append_vertices(read_change_record(r), body);
    write_ply(path, body);
}

}  // namespace ltm::maintenance
