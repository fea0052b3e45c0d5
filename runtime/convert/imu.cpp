#include "runtime/convert/imu.hpp"

#include <cmath>

#include "runtime/convert/dds_string.hpp"
#include "runtime/convert/geometry.hpp"

namespace ltm::convert {

Owned<msg::Imu> to_msg(const ImuData& d) {
    Owned<msg::Imu> m;
    m->header.stamp = to_time(d.stamp);
    set_string(m->header.frame_id, d.frame_id);
    m->orientation = {0.0, 0.0, 0.0, 1.0};
    m->orientation_covariance[0] = -1.0;  // no orientation estimate
    m->angular_velocity = {d.angular_velocity.x(), d.angular_velocity.y(), d.angular_velocity.z()};
    m->linear_acceleration = {d.linear_acceleration.x(), d.linear_acceleration.y(),
                              d.linear_acceleration.z()};
    for (int k = 0; k < 3; ++k) {
        m->angular_velocity_covariance[4 * k] = d.gyro_variance;
        m->linear_acceleration_covariance[4 * k] = d.accel_variance;
    }
    return m;
}

std::string from_msg(const msg::Imu& m, ImuData* d) {
    d->stamp = to_seconds(m.header.stamp);
    d->frame_id = to_string(m.header.frame_id);
    const auto& w = m.angular_velocity;
    const auto& a = m.linear_acceleration;
    d->angular_velocity = {w.x, w.y, w.z};
    d->linear_acceleration = {a.x, a.y, a.z};
    d->gyro_variance = m.angular_velocity_covariance[0];
    d->accel_variance = m.linear_acceleration_covariance[0];
    if (!d->angular_velocity.allFinite()) return "IMU angular velocity is not finite";
    if (!std::isfinite(d->stamp)) return "IMU stamp is not finite";
    return "";
}

}  // namespace ltm::convert
