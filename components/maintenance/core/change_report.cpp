#include "maintenance/core/change_report.hpp"

#include <cstdio>
#include <cstring>

#include "common/core/file_io.hpp"

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

void write_change_ply(const std::string& path, const ChangeSet& changes) {
    std::size_t n = 0;
    for (const SegmentChange& s : changes.changes) n += s.voxels.size();
    std::string bytes =
        "ply\nformat binary_little_endian 1.0\ncomment ltm map changes: removed red, added "
        "green\nelement vertex " +
        std::to_string(n) +
        "\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\n"
        "property uchar green\nproperty uchar blue\nend_header\n";
    const std::size_t header = bytes.size();
    bytes.resize(header + n * 15);
    char* out = bytes.data() + header;
    for (const SegmentChange& s : changes.changes) {
        const unsigned char rgb[3] = {static_cast<unsigned char>(s.removed() ? 220 : 30),
                                      static_cast<unsigned char>(s.removed() ? 30 : 200), 30};
        for (const Eigen::Vector3f& p : s.voxels) {
            std::memcpy(out, p.data(), 12);
            std::memcpy(out + 12, rgb, 3);
            out += 15;
        }
    }
    common::write_file_atomic(path, bytes);
}

}  // namespace ltm::maintenance
