#include "localisation/core/global_query.hpp"

#include <sstream>

namespace ltm::localisation {

GlobalAnswer answer(GlobalLocaliser& global, const GlobalRequest& request) {
    GlobalAnswer a;
    a.id = request.id;
    a.stamp = request.stamp;
    a.T_odom_lidar = request.T_odom_lidar;
    a.segment = request.segment;
    a.result = global.localise(request.points, request.hint);
    return a;
}

Eigen::Isometry3d answer_T_map_odom(const GlobalAnswer& a) {
    return a.result.T_map_lidar * a.T_odom_lidar.inverse();
}

Eigen::Isometry3d carry_forward(const GlobalAnswer& a, const Eigen::Isometry3d& T_odom_lidar_now) {
    return answer_T_map_odom(a) * T_odom_lidar_now;
}

std::optional<GlobalRequest> GlobalHandOver::ask(double stamp,
                                                 const std::vector<Eigen::Vector3f>& points,
                                                 const Eigen::Isometry3d& T_odom_lidar,
                                                 std::uint32_t segment,
                                                 const std::optional<PoseHint>& hint) {
    if (out_) return std::nullopt;
    GlobalRequest r;
    r.id = next_id_++;
    r.stamp = stamp;
    r.points = points;
    r.T_odom_lidar = T_odom_lidar;
    r.segment = segment;
    r.hint = hint;
    out_ = Out{r.id, stamp, hint_generation_};
    return r;
}

GlobalHandOver::Fate GlobalHandOver::receive(const GlobalAnswer& a, std::uint32_t segment_now,
                                             std::string* why) {
    if (!out_ || out_->id != a.id) return Fate::kUnknown;
    const Out out = *out_;
    out_.reset();
    std::ostringstream s;
    s.precision(3);
    if (a.segment != segment_now) {
        s << "the global localisation of the scan at " << std::fixed << a.stamp
          << " s is dropped: the odometry restarted since (segment " << segment_now << ")";
    } else if (out.hint_generation != hint_generation_) {
        s << "the global localisation of the scan at " << std::fixed << a.stamp
          << " s is dropped: an initial pose came since";
    }
    if (why) *why = s.str();
    return s.str().empty() ? Fate::kApply : Fate::kStale;
}

}  // namespace ltm::localisation
