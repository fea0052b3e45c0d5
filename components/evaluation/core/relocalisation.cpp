#include "evaluation/core/relocalisation.hpp"

#include "evaluation/core/rpe.hpp"

namespace ltm::eval {

RelocResult evaluate_relocalisation(const RelocAttempts& attempts,
                                    const common::PoseList& reference, const RelocConfig& config) {
    RelocResult r;
    std::vector<double> t_all, t_ok, e_t, e_r;
    for (const auto& a : attempts) {
        if (a.frame >= reference.size()) {
            ++r.out_of_range;
            continue;
        }
        ++r.attempts;
        t_all.push_back(a.time_s);
        if (!a.has_pose) {
            ++r.no_pose;
            continue;
        }
        const Eigen::Isometry3d err = reference[a.frame].inverse() * a.pose;
        const double et = err.translation().norm();
        const double er = rotation_angle(err.linear()) * 180.0 / M_PI;
        if (et <= config.max_translation && er <= config.max_rotation_deg) {
            ++r.successes;
            t_ok.push_back(a.time_s);
            e_t.push_back(et);
            e_r.push_back(er);
        } else {
            ++r.wrong;
        }
    }
    r.success_rate = r.attempts ? static_cast<double>(r.successes) / r.attempts : 0.0;
    r.time_all_s = summarize(t_all);
    r.time_success_s = summarize(t_ok);
    r.translation_error = summarize(e_t);
    r.rotation_error_deg = summarize(e_r);
    return r;
}

}  // namespace ltm::eval
