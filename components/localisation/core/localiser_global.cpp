// The Localiser's global localisation elsewhere (Localiser::set_global_elsewhere): the query asked
// for a scan and its answer applied to a later one, carried forward by the odometry
// (global_query.hpp).
#include <sstream>

#include "localisation/core/localiser.hpp"

namespace ltm::localisation {

std::optional<GlobalRequest> Localiser::take_request() {
    std::optional<GlobalRequest> r;
    r.swap(request_);
    return r;
}

void Localiser::ask_global(double stamp, const std::vector<Eigen::Vector3f>& points,
                           const Eigen::Isometry3d& T_odom_lidar, LocalisationUpdate* u) {
    std::ostringstream s;
    s.precision(3);
    s << std::fixed;
    if (auto r = handover_.ask(stamp, points, T_odom_lidar, segment_, hint_)) {
        last_global_ = stamp;
        request_ = std::move(r);
        recheck_ = false;
        u->global_asked = true;
        s << "global localisation asked for this scan";
    } else {
        s << "global localisation running (for the scan at " << handover_.asked_stamp() << " s)";
    }
    u->message = u->message.empty() ? s.str() : u->message + "; " + s.str();
}

bool Localiser::apply_answer(double stamp, const Eigen::Isometry3d& T_odom_lidar,
                             LocalisationUpdate* u) {
    const GlobalAnswer a = std::move(*answer_);
    answer_.reset();
    std::string why;
    const GlobalHandOver::Fate fate = handover_.receive(a, segment_, &why);
    if (fate == GlobalHandOver::Fate::kUnknown) return false;
    u->global_ran = true;
    u->global_time_s = a.result.time_s;
    u->global_carried_s = stamp - a.stamp;
    if (fate == GlobalHandOver::Fate::kStale) {
        u->message = why;
        last_global_ = -1e300;  // ask again at once
        recheck_ = true;
        return false;
    }
    const GlobalLocalisation& g = a.result;
    if (!g.localised) {
        u->message = "not localised: " + g.reason;
        return false;
    }
    hint_.reset();
    // The answer's scan carried forward to this one by the odometry, then registered on this
    // scan (tracking): the pose of now, never the answer's from the past.
    T_map_odom_ = answer_T_map_odom(a);
    const Eigen::Isometry3d carried = carry_forward(a, T_odom_lidar);
    // Paged: tracking goes on at once on the local maps the answer was verified on.
    if (neighbourhood_) neighbourhood_->adopt(g.around, carried.translation());
    LocalisationUpdate refined = *u;
    if (track(carried, &refined)) {
        *u = refined;
        T_map_odom_ = u->T_map_lidar * T_odom_lidar.inverse();
    } else {
        T_map_lidar_ = carried;
        u->T_map_lidar = carried;
        u->covariance = g.covariance;
        u->confidence = g.confidence;
        u->inlier_fraction = g.inlier_fraction;
    }
    std::ostringstream s;
    s.precision(3);
    s << "relocalised: " << g.reason << " (the scan at " << std::fixed << a.stamp
      << " s, carried forward " << stamp - a.stamp << " s by the odometry"
      << (refined.message.empty() ? "" : "; " + refined.message) << ")";
    u->message = s.str();
    state_ = LocalisationState::kRelocalised;
    have_fix_ = true;
    last_fix_ = last_good_ = stamp;
    return true;
}

}  // namespace ltm::localisation
