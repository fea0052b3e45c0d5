#pragma once
// The localisation component's scans paired with the odometry's pose of the same stamp (the
// component's thread): a scan waits until that pose comes, or the odometry says it has none for it
// (a newer pose, or a status line of that scan saying lost, skipped, rejected or bad cloud); while
// no odometry runs (none matched), at most odometry_wait_s of wall time. Each pose carries the
// odometry segment of its scan (the one its newest restart up to the scan started).
#include <cstdint>
#include <functional>
#include <optional>
#include <utility>
#include <vector>

#include "common/core/point_cloud.hpp"
#include "localisation/core/localiser.hpp"
#include "registration/core/se3.hpp"
#include "runtime/convert/odometry.hpp"
#include "runtime/convert/status.hpp"
#include "runtime/stamp_pairer.hpp"

namespace ltm::localisation {

// A scan on its way to the worker, with the odometry's pose and twist when they came in time.
struct Scan {
    std::uint64_t index = 0;
    common::PointCloud cloud;
    std::optional<OdometryInput> odometry;
    registration::Vector6d velocity = registration::Vector6d::Zero();  // [v; w], LiDAR frame
};

class ScanPairing {
  public:
    using Submit = std::function<void(Scan&&)>;

    explicit ScanPairing(double odometry_wait_s);

    void add_scan(Scan&& scan);  // at its cloud's stamp
    void add_pose(convert::OdometryData&& pose);
    // Another component's status line: true when it said the odometry has no pose for a scan
    // (pairing may release it now).
    bool status(const convert::StatusData& s);

    // Hands on every scan whose pose came or will not come. `odometry_running` (its writer
    // matched): its pose, a newer one or its "no pose" status will come: waited for however late
    // (a loaded machine's odometry was more than odometry_wait_s behind and scans went on without
    // their poses: tracking from a guess, wrong fixes).
    void release(bool odometry_running, const Submit& submit);
    // Every scan still waiting, without its pose (shutdown).
    void release_all(const Submit& submit);

  private:
    std::uint32_t segment_at(double stamp) const;

    double wait_s_;
    runtime::StampPairer<Scan, convert::OdometryData> pairer_;
    std::vector<std::pair<double, std::uint32_t>> restarts_;  // the odometry's: stamp, segment
};

}  // namespace ltm::localisation
