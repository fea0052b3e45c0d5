#include "maintenance/component/maintenance_params.hpp"

#include <optional>
#include <type_traits>

namespace ltm::maintenance {

namespace {
template <class T>
struct is_optional : std::false_type {};
template <class T>
struct is_optional<std::optional<T>> : std::true_type {};
}  // namespace

MaintenanceComponentConfig load_maintenance_params(runtime::Parameters& p) {
    MaintenanceComponentConfig c;
    const std::string input = p.get<std::string>("input", "odometry");
    if (input == "odometry") {
        c.input = PoseInput::kOdometry;
    } else if (input == "pose") {
        c.input = PoseInput::kPose;
    } else if (input == "pose_with_covariance") {
        c.input = PoseInput::kPoseWithCovariance;
    } else {
        p.fail("input", "expected odometry, pose or pose_with_covariance, got '" + input + "'");
    }
    c.output_dir = p.path("output_dir", "", runtime::PathCheck::kNone);
    c.maintain_every_s = p.get<double>("maintain_every_s", c.maintain_every_s);
    if (!(c.maintain_every_s >= 0.0))
        p.fail("maintain_every_s", "must be >= 0 (0: only at shutdown)");
    c.map_file = p.path("map_file", "", runtime::PathCheck::kNone);
    c.site_dir = p.path("site_dir", "", runtime::PathCheck::kNone);
    c.site_version = p.get<std::string>("site_version", "");
    if (!c.site_dir.empty() && !c.map_file.empty())
        p.fail("map_file", "give either map_file or site_dir, not both");
    if (c.site_dir.empty() && !c.site_version.empty()) p.fail("site_version", "needs site_dir");
    c.session = p.get<int>("session", c.session);
    if (c.session < -1) p.fail("session", "must be >= 0 (or -1: after the map's last session)");
    c.max_queue = p.get<int>("max_queue", c.max_queue);
    if (c.max_queue < 1) p.fail("max_queue", "must be >= 1");
    c.skip_while_busy = p.get<bool>("skip_while_busy", c.skip_while_busy);
    c.pack_after = p.get<int>("pack_after", c.pack_after);
    if (c.pack_after < -1) p.fail("pack_after", "must be >= 0 (or -1: never packed)");
    c.cpu_share = p.get<double>("cpu_share", c.cpu_share);
    if (!(c.cpu_share > 0.0 && c.cpu_share <= 1.0))
        p.fail("cpu_share", "must be in (0, 1] (1: not paced)");
    c.cpu_budget = p.get<std::string>("cpu_budget", c.cpu_budget);
    c.max_queue_mb = p.get<double>("max_queue_mb", c.max_queue_mb);
    if (!(c.max_queue_mb >= 0.0)) p.fail("max_queue_mb", "must be >= 0 (0: only max_queue bounds)");
    c.paging_radius = p.get<double>("paging_radius", c.paging_radius);
    if (!(c.paging_radius >= 0.0)) p.fail("paging_radius", "must be >= 0 (0: no paging)");
    c.paging_dir = p.path("paging_dir", "", runtime::PathCheck::kNone);
    c.views.distance = p.get<double>("view_distance", c.views.distance);
    c.views.angle_deg = p.get<double>("view_angle", c.views.angle_deg);
    c.views.interval_s = p.get<double>("view_interval_s", c.views.interval_s);
    if (const auto problem = validate(c.views)) {
        const auto colon = problem->find(':');
        p.fail(problem->substr(0, colon), problem->substr(colon + 2));
    }
    visit_fields(c.maintenance, "", [&](const std::string& key, auto& field, const auto& /*rule*/) {
        using T = std::decay_t<decltype(field)>;
        if constexpr (is_optional<T>::value) {
            // A time-dependent key: as given, else unset (derived from the data). Read even when
            // absent, so that a misspelt key is named beside it.
            const auto value = p.get<typename T::value_type>(key, {});
            if (p.has(key)) field = value;
        } else {
            field = p.get(key, field);
        }
    });
    if (const auto problem = validate(c.maintenance)) p.fail(problem->key, problem->problem);
    return c;
}

}  // namespace ltm::maintenance
