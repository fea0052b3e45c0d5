// One simulated scan: pulses from the sensor pose (at each pulse's time with motion
// distortion), actors posed at the pulse time, detection, noise, intensity and labels.
#include <algorithm>
#include <array>
#include <cmath>

#include "simulator/core/random.hpp"
#include "simulator/core/simulator.hpp"

namespace ltm::sim {
namespace {

constexpr int kSensorSteps = 128;  // sensor poses a sweep (motion distortion)
constexpr int kActorSteps = 16;    // actor poses a sweep (motion distortion)

// An actor close enough to be hit in this scan: its azimuth window in the sensor frame.
struct NearActor {
    int actor;
    float azimuth, half_width;  // [rad]
    std::array<Eigen::Isometry3f, kActorSteps> T_actor_world;
};

float wrap(float a) {
    while (a > float(M_PI)) a -= float(2 * M_PI);
    while (a < -float(M_PI)) a += float(2 * M_PI);
    return a;
}

int step_of(float time, double period, int steps) {
    return std::clamp(static_cast<int>(time / period * steps), 0, steps - 1);
}

}  // namespace

float Simulator::albedo(const SurfaceHit& hit, const Eigen::Vector3f& point) const {
    // Surfaces of one material differ (paint, dirt, wear): each object by up to +-25 %, the
    // ground in 2 m patches by up to +-20 %. Independent of the session: an object looks the same.
    if (hit.actor || hit.object != 0) {
        return 0.75f + 0.5f * static_cast<float>(hash_unit(hash_mix(albedo_key_, hit.object)));
    }
    const auto cx = static_cast<std::int64_t>(std::floor(point.x() / 2.0f));
    const auto cy = static_cast<std::int64_t>(std::floor(point.y() / 2.0f));
    return 0.8f +
           0.4f * static_cast<float>(hash_unit(hash_mix(albedo_key_, static_cast<std::uint64_t>(cx),
                                                        static_cast<std::uint64_t>(cy))));
}

bool Simulator::scan(std::size_t i, SimScan& out) const {
    if (i >= slots_.size()) return false;
    const Slot& slot = slots_[i];
    const SensorConfig& sc = sensor_.config();
    const double period = sensor_.period();
    const bool distort = sc.motion_distortion;
    const double session_time =
        slot.stamp - scenario_.sessions[static_cast<std::size_t>(session_)].start_time;

    out.index = i;
    out.after_kidnap = slot.kidnap;
    out.T_world_lidar = path_->pose_at(slot.route_time, terrain_, sc.height);
    out.cloud.clear();
    out.cloud.stamp = slot.stamp;
    out.cloud.frame_id = "lidar";
    out.labels.clear();
    out.rings.clear();

    // Sensor poses through the sweep (motion distortion only).
    const Eigen::Isometry3f T0 = out.T_world_lidar.cast<float>();
    std::vector<Eigen::Isometry3f> sensor_steps;
    float sweep_motion = 0.0f, sweep_turn = 0.0f;
    if (distort) {
        sensor_steps.resize(kSensorSteps);
        for (int k = 0; k < kSensorSteps; ++k) {
            const double t = slot.route_time + period * (k + 0.5) / kSensorSteps;
            sensor_steps[static_cast<std::size_t>(k)] =
                path_->pose_at(t, terrain_, sc.height).cast<float>();
        }
        for (const auto& T : sensor_steps) {
            sweep_motion = std::max(sweep_motion, (T.translation() - T0.translation()).norm());
            sweep_turn = std::max(sweep_turn,
                                  Eigen::AngleAxisf(T0.linear().transpose() * T.linear()).angle());
        }
    }

    // Actors in range, each with the azimuth window (sensor frame) its pulses can come from.
    std::vector<NearActor> near;
    const Eigen::Isometry3f T0_inv = T0.inverse();
    for (std::size_t j = 0; j < actors_.size(); ++j) {
        const Actor& a = actors_[j];
        const Eigen::Isometry3d mid = a.pose_at(session_time + 0.5 * period, terrain_);
        const Eigen::Vector3f c = T0_inv * mid.translation().cast<float>();
        const float d_xy = c.head<2>().norm();
        const float speed =
            static_cast<float>((a.pose_at(session_time + period, terrain_).translation() -
                                a.pose_at(session_time, terrain_).translation())
                                   .norm());
        const float radius =
            world_.prototype_radius(actor_prototype_[j]) + speed + sweep_motion + 0.3f;
        if (d_xy - radius > sc.max_range) continue;
        NearActor n;
        n.actor = static_cast<int>(j);
        n.azimuth = std::atan2(c.y(), c.x());
        n.half_width =
            d_xy > radius ? std::asin(radius / d_xy) + sweep_turn + 0.01f : float(M_PI) + 1.0f;
        for (int k = 0; k < (distort ? kActorSteps : 1); ++k) {
            const double t =
                distort ? session_time + period * (k + 0.5) / kActorSteps : session_time;
            n.T_actor_world[static_cast<std::size_t>(k)] =
                a.pose_at(t, terrain_).cast<float>().inverse();
        }
        near.push_back(n);
    }

    // Pulses: cast, detect, add noise, label.
    std::vector<Pulse> scratch;
    const std::vector<Pulse>& pulses = sensor_.pulses(i, scratch);
    // Times only describe a sweep when the points were taken along it: an undistorted scan is a
    // snapshot at its stamp, and per-point times would make a de-skew distort it.
    const bool with_time = sc.per_point_time && distort;
    out.cloud.reserve(pulses.size(), true, with_time);
    out.labels.reserve(pulses.size());
    out.rings.reserve(pulses.size());
    std::vector<ActorView> views;
    views.reserve(near.size());
    const std::uint64_t key = hash_mix(scan_key_, i);
    const float max_range = static_cast<float>(sc.max_range);
    for (std::size_t k = 0; k < pulses.size(); ++k) {
        const Pulse& p = pulses[k];
        if (p.blocked) continue;
        const Eigen::Isometry3f& T =
            distort ? sensor_steps[static_cast<std::size_t>(step_of(p.time, period, kSensorSteps))]
                    : T0;
        views.clear();
        for (const NearActor& n : near) {
            if (std::abs(wrap(p.azimuth - n.azimuth)) > n.half_width) continue;
            const int step = distort ? step_of(p.time, period, kActorSteps) : 0;
            views.push_back({actor_prototype_[static_cast<std::size_t>(n.actor)],
                             actors_[static_cast<std::size_t>(n.actor)].id(),
                             n.T_actor_world[static_cast<std::size_t>(step)]});
        }
        const Eigen::Vector3f dir = T.linear() * p.dir;
        const Eigen::Vector3f origin = T.translation() + T.linear().col(2) * p.origin_z;
        const std::uint64_t h = hash_mix(key, k);
        SurfaceHit hit;
        const int n_views = static_cast<int>(views.size());
        if (!world_.cast(origin, dir, max_range, views.data(), n_views, h, hit)) continue;
        if (hit.range < sc.min_range) continue;  // too near to measure
        const double reflectivity =
            material_properties(hit.material).reflectivity * albedo(hit, origin + dir * hit.range);
        const double cos_incidence = std::abs(hit.normal.dot(dir));
        const double power = sensor_.return_power(reflectivity, cos_incidence, hit.range);
        const double p_return = SensorModel::detection_probability(power) * (1.0 - sc.dropout);
        if (hash_unit(hash_mix(h, 1)) >= p_return) continue;
        const double range = hit.range + sc.range_noise * hash_normal(hash_mix(h, 2));
        if (range < sc.min_range || range > sc.max_range) continue;
        const double intensity = SensorModel::intensity(reflectivity, power) *
                                     (1.0 + sc.intensity_noise * hash_normal_fast(hash_mix(h, 3))) +
                                 0.02 * hash_normal_fast(hash_mix(h, 4));
        out.cloud.points.push_back(p.dir * static_cast<float>(range) +
                                   Eigen::Vector3f(0, 0, p.origin_z));
        out.cloud.intensity.push_back(static_cast<float>(std::clamp(intensity, 0.0, 1.0)));
        if (with_time) out.cloud.time.push_back(p.time);
        out.labels.push_back(label_of(hit));
        out.rings.push_back(p.ring);
    }
    return true;
}

}  // namespace ltm::sim
