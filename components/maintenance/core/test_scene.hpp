#pragma once
// Small ray-cast scenes for the maintenance tests: boxes on a flat ground z = 0 seen by a
// 32-beam LiDAR (30 deg of elevation, 0.4 deg columns), exact ground truth per point.
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <vector>

namespace ltm::maintenance::test {

struct Box {
    Eigen::Vector3f lo, hi;
    int id;
};

// The scan of `boxes` and the ground z = 0 from a sensor at `pose` (world frame), in the sensor
// frame; hit_id[i] is the box a point came from (-1 ground).
inline std::vector<Eigen::Vector3f> cast(const std::vector<Box>& boxes,
                                         const Eigen::Isometry3d& pose,
                                         std::vector<int>* hit_id = nullptr,
                                         float max_range = 40.0f) {
    std::vector<Eigen::Vector3f> pts;
    if (hit_id) hit_id->clear();
    const Eigen::Vector3f o = pose.translation().cast<float>();
    const Eigen::Matrix3f R = pose.linear().cast<float>();
    for (int ring = 0; ring < 32; ++ring) {
        const float el = float((-20.0 + 30.0 * ring / 31.0) * M_PI / 180.0);
        for (int k = 0; k < 900; ++k) {
            const float az = float((-180.0 + 0.4 * k) * M_PI / 180.0);
            const Eigen::Vector3f d_s(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az),
                                      std::sin(el));
            const Eigen::Vector3f d = R * d_s;
            float best = max_range;
            int id = -2;
            if (d.z() < -1e-6f) {
                const float t = -o.z() / d.z();
                if (t < best) {
                    best = t;
                    id = -1;
                }
            }
            for (const Box& b : boxes) {
                float t0 = 0.0f, t1 = best;
                bool hit = true;
                for (int a = 0; a < 3 && hit; ++a) {
                    if (std::abs(d[a]) < 1e-9f) {
                        hit = o[a] >= b.lo[a] && o[a] <= b.hi[a];
                        continue;
                    }
                    float ta = (b.lo[a] - o[a]) / d[a], tb = (b.hi[a] - o[a]) / d[a];
                    if (ta > tb) std::swap(ta, tb);
                    t0 = std::max(t0, ta);
                    t1 = std::min(t1, tb);
                    hit = t0 <= t1;
                }
                if (hit && t0 > 0.0f && t0 < best) {
                    best = t0;
                    id = b.id;
                }
            }
            if (id == -2) continue;
            pts.push_back(d_s * best);
            if (hit_id) hit_id->push_back(id);
        }
    }
    return pts;
}

}  // namespace ltm::maintenance::test
