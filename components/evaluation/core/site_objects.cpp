#include "evaluation/core/site_objects.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <unordered_map>

#include "common/core/io_error.hpp"

namespace ltm::eval {

bool SiteObject::contains(const Eigen::Vector3d& p, double margin) const {
    const double yaw = yaw_deg * M_PI / 180.0;
    const double dx = p.x() - x, dy = p.y() - y;
    const double along = std::cos(yaw) * dx + std::sin(yaw) * dy;
    const double across = -std::sin(yaw) * dx + std::cos(yaw) * dy;
    return std::abs(along) <= 0.5 * length + margin && std::abs(across) <= 0.5 * width + margin &&
           p.z() >= base_z - margin && p.z() <= base_z + height + margin;
}

double SiteObject::ground_at(const Eigen::Vector3d& p) const {
    if (ground_z.size() < 2) return base_z;
    const double yaw = yaw_deg * M_PI / 180.0;
    const double along = std::cos(yaw) * (p.x() - x) + std::sin(yaw) * (p.y() - y);
    const double steps = double(ground_z.size() - 1);
    const double t =
        length > 0.0 ? std::clamp((along / length + 0.5) * steps, 0.0, steps) : 0.5 * steps;
    const std::size_t k = std::min(std::size_t(t), ground_z.size() - 2);
    const double f = t - double(k);
    return (1.0 - f) * ground_z[k] + f * ground_z[k + 1];
}

std::vector<SiteObject> read_site_objects(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw common::IoError(path, "cannot read");
    std::vector<SiteObject> out;
    std::string line;
    for (int n = 1; std::getline(in, line); ++n) {
        const auto hash = line.find('#');
        if (hash != std::string::npos) line.resize(hash);
        std::istringstream s(line);
        SiteObject o;
        if (!(s >> o.id)) {
            if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
            throw common::IoError(path, "line " + std::to_string(n) + ": expected an object id");
        }
        int changed = 0;
        if (!(s >> o.kind >> o.x >> o.y >> o.base_z >> o.yaw_deg >> o.length >> o.width >>
              o.height >> changed) ||
            !std::isfinite(o.x + o.y + o.base_z + o.yaw_deg) || o.length < 0.0 || o.width < 0.0 ||
            o.height < 0.0) {
            throw common::IoError(path, "line " + std::to_string(n) +
                                            ": expected `id kind x y base_z yaw_deg length width "
                                            "height changed`");
        }
        o.changed = changed != 0;
        for (double z; s >> z;) o.ground_z.push_back(z);
        const bool bad_ground = !s.eof() || o.ground_z.size() == 1 ||
                                std::any_of(o.ground_z.begin(), o.ground_z.end(),
                                            [](double z) { return !std::isfinite(z); });
        if (bad_ground)
            throw common::IoError(path, "line " + std::to_string(n) +
                                            ": the ground heights after `changed` must be numbers, "
                                            "none or at least two");
        out.push_back(o);
    }
    return out;
}

ObjectChanges diff_objects(const std::vector<SiteObject>& first,
                           const std::vector<SiteObject>& later, double move_tolerance) {
    std::unordered_map<std::uint32_t, const SiteObject*> in_later, in_first;
    for (const auto& o : later) in_later[o.id] = &o;
    for (const auto& o : first) in_first[o.id] = &o;
    ObjectChanges out;
    for (const auto& o : first) {
        const auto it = in_later.find(o.id);
        if (it == in_later.end()) {
            out.removed.push_back(o);
            continue;
        }
        const SiteObject& n = *it->second;
        const double shift = std::hypot(n.x - o.x, n.y - o.y);
        const double turn = std::abs(std::remainder(n.yaw_deg - o.yaw_deg, 360.0));
        if (shift > move_tolerance || turn > 1.0) {
            out.moved_from.push_back(o);
            out.moved_to.push_back(n);
        }
    }
    for (const auto& o : later)
        if (!in_first.count(o.id)) out.added.push_back(o);
    return out;
}

}  // namespace ltm::eval
