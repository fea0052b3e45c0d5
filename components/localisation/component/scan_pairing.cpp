#include "localisation/component/scan_pairing.hpp"

#include <algorithm>
#include <limits>

#include "common/core/status_code.hpp"
#include "runtime/convert/geometry.hpp"

namespace ltm::localisation {
namespace {

constexpr double kSameStamp = 1e-4;        // a scan and its odometry pose [s]
constexpr std::size_t kMaxOdometry = 200;  // odometry poses kept for pairing

}  // namespace

ScanPairing::ScanPairing(double odometry_wait_s)
    : wait_s_(odometry_wait_s),
      pairer_(runtime::StampPairerOptions{kSameStamp, kMaxOdometry, 0, kMaxOdometry,
                                          odometry_wait_s}) {}

void ScanPairing::add_scan(Scan&& scan) {
    const double stamp = scan.cloud.stamp;
    pairer_.add_scan(stamp, std::move(scan));
}

void ScanPairing::add_pose(convert::OdometryData&& pose) {
    const double stamp = convert::to_seconds(pose.stamp);
    pairer_.add_pose(stamp, std::move(pose));
}

bool ScanPairing::status(const convert::StatusData& s) {
    const double stamp = convert::to_seconds(s.stamp);
    if (s.code == common::StatusCode::kRestarted) {
        restarts_.emplace_back(stamp, s.segment);
    } else if (common::says_no_pose(s.code)) {  // lost, skipped, rejected, bad cloud
        pairer_.add_no_pose(stamp);
        return true;
    }
    return false;
}

void ScanPairing::release(bool odometry_running, const Submit& submit) {
    pairer_.set_wait_s(odometry_running ? std::numeric_limits<double>::infinity() : wait_s_);
    pairer_.release([&](double stamp, Scan&& s, std::optional<convert::OdometryData>&& o) {
        if (o) {
            s.odometry = OdometryInput{o->T_parent_child, segment_at(stamp)};
            s.velocity << o->linear_velocity, o->angular_velocity;
        }
        submit(std::move(s));
    });
}

void ScanPairing::release_all(const Submit& submit) {
    pairer_.release_all(
        [&](double, Scan&& s, std::optional<convert::OdometryData>&&) { submit(std::move(s)); });
}

std::uint32_t ScanPairing::segment_at(double stamp) const {
    std::uint32_t segment = 0;
    for (const auto& [restart, number] : restarts_)
        if (restart <= stamp + kSameStamp) segment = std::max(segment, number);
    return segment;
}

}  // namespace ltm::localisation
