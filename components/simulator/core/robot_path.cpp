#include "simulator/core/robot_path.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/core/io_error.hpp"
#include "common/core/kitti_io.hpp"

namespace ltm::sim {

std::string resolve_path(const std::string& path, const std::string& base_dir) {
    if (path.empty() || path[0] == '/' || base_dir.empty()) return path;
    return base_dir + "/" + path;
}

namespace {

// Unit direction from a to b; zero when they coincide.
Eigen::Vector2d direction(const Waypoint& a, const Waypoint& b) {
    const Eigen::Vector2d d(b.x - a.x, b.y - a.y);
    return d.norm() > 1e-9 ? Eigen::Vector2d(d.normalized()) : Eigen::Vector2d::Zero();
}

bool reverses(const Eigen::Vector2d& d_in, const Eigen::Vector2d& d_out) {
    return d_in.dot(d_out) < std::cos(120.0 * M_PI / 180.0);
}

// A turning loop at b for a robot heading d: right a little, round to the left, back to b.
void append_turning_loop(const Waypoint& b, const Eigen::Vector2d& d, double radius,
                         std::vector<Waypoint>& out) {
    const Eigen::Vector2d p(b.x, b.y), n(-d.y(), d.x());
    for (const Eigen::Vector2d& q :
         {Eigen::Vector2d(p + 4 * radius * d - 2 * radius * n), Eigen::Vector2d(p + 6 * radius * d),
          Eigen::Vector2d(p + 4 * radius * d + 2 * radius * n), p}) {
        out.push_back({q.x(), q.y(), 0.0});
    }
}

}  // namespace

std::vector<Waypoint> route_laps(const RouteConfig& config) {
    const std::vector<Waypoint>& w = config.waypoints;
    if (config.laps <= 1 || w.size() < 2) return w;
    // Heading on the last leg and on the first (skipping repeated points).
    Eigen::Vector2d d_last = Eigen::Vector2d::Zero(), d_first = Eigen::Vector2d::Zero();
    for (std::size_t i = w.size() - 1; i > 0 && d_last.isZero(); --i)
        d_last = direction(w[i - 1], w[i]);
    for (std::size_t i = 1; i < w.size() && d_first.isZero(); ++i)
        d_first = direction(w[i - 1], w[i]);
    const double radius = std::max(config.corner_radius, 2.0);
    const Waypoint& last = w.back();
    const Waypoint& first = w.front();
    const Eigen::Vector2d leg = direction(last, first);
    std::vector<Waypoint> between;  // driven after the last waypoint, before the first again
    if (leg.isZero()) {  // a closed route: only the turn from the last leg into the first
        if (reverses(d_last, d_first)) append_turning_loop(last, d_last, radius, between);
    } else {
        if (reverses(d_last, leg)) append_turning_loop(last, d_last, radius, between);
        if (reverses(leg, d_first)) {
            between.push_back({first.x, first.y, 0.0});
            append_turning_loop(first, leg, radius, between);
            between.pop_back();  // the loop ends at the first waypoint, which follows
        }
    }
    std::vector<Waypoint> out = w;
    for (int lap = 1; lap < config.laps; ++lap) {
        out.insert(out.end(), between.begin(), between.end());
        out.insert(out.end(), w.begin(), w.end());
    }
    return out;
}

RobotPath::RobotPath(const RouteConfig& config, const std::string& base_dir) {
    if (!config.poses_file.empty()) {
        init_file(config, base_dir);
    } else {
        init_waypoints(config);
    }
}

void RobotPath::init_waypoints(const RouteConfig& config) {
    if (config.waypoints.size() < 2)
        throw ScenarioError("route: needs at least two waypoints or a poses_file");
    if (config.speed <= 0) throw ScenarioError("route.speed: must be > 0");
    const std::vector<Waypoint> waypoints = route_laps(config);
    // Corners are rounded between turns on the spot; where the robot turns on the spot the
    // corner stays sharp. Each piece starts where the previous one ended.
    Points2 pts;
    std::vector<std::size_t> index(waypoints.size(), 0);
    for (std::size_t begin = 0, end = 1; end < waypoints.size(); ++end) {
        if (end + 1 < waypoints.size() && !(waypoints[end].spin_time > 0)) continue;
        Points2 piece;
        for (std::size_t k = begin; k <= end; ++k)
            piece.emplace_back(waypoints[k].x, waypoints[k].y);
        std::vector<std::size_t> piece_index;
        const Points2 rounded = round_corners(piece, config.corner_radius, 0.5, &piece_index);
        const std::size_t base = pts.empty() ? 0 : pts.size() - 1;
        pts.insert(pts.end(), rounded.begin() + (pts.empty() ? 0 : 1), rounded.end());
        for (std::size_t k = begin; k <= end; ++k) index[k] = base + piece_index[k - begin];
        begin = end;
    }
    line_ = Polyline(pts);
    if (line_.length() <= 0) throw ScenarioError("route: the waypoints do not move the robot");
    waypoint_vertex_ = index;
    // The speed of waypoint i holds until waypoint i + 1.
    vertex_time_.assign(line_.points().size(), 0.0);
    std::size_t leg = 0;
    for (std::size_t j = 1; j < line_.points().size(); ++j) {
        while (leg + 1 < index.size() && index[leg + 1] < j) ++leg;
        const double v = waypoints[leg].speed > 0 ? waypoints[leg].speed : config.speed;
        vertex_time_[j] = vertex_time_[j - 1] + (line_.vertex_s(j) - line_.vertex_s(j - 1)) / v;
    }
    // Turns on the spot: from the heading driving in to the heading driving out, the way and
    // the number of whole turns the waypoint asks for.
    const double inf = std::numeric_limits<double>::infinity();
    double spun = 0.0;
    for (std::size_t i = 0; i < waypoints.size(); ++i) {
        if (!(waypoints[i].spin_time > 0)) continue;
        Spin sp;
        sp.vertex = index[i];
        sp.s = line_.vertex_s(sp.vertex);
        sp.t0 = vertex_time_[sp.vertex] + spun;
        sp.duration = waypoints[i].spin_time;
        sp.angle = waypoints[i].spin_deg * M_PI / 180.0;  // as asked; made exact below
        spins_.push_back(sp);
        spun += sp.duration;
    }
    for (std::size_t k = 0; k < spins_.size(); ++k) {
        Spin& sp = spins_[k];
        const double lo = k > 0 ? spins_[k - 1].s : -inf;
        const double hi = k + 1 < spins_.size() ? spins_[k + 1].s : inf;
        sp.yaw0 = heading_at(sp.s, lo, sp.s);
        const double turn = std::remainder(heading_at(sp.s, sp.s, hi) - sp.yaw0, 2 * M_PI);
        sp.angle = turn + 2 * M_PI * std::round((sp.angle - turn) / (2 * M_PI));  // as asked
    }
}

RobotPath::Phase RobotPath::phase(double t) const {
    Phase ph;
    double spun = 0.0;
    for (const Spin& sp : spins_) {
        if (t <= sp.t0) break;
        if (t < sp.t0 + sp.duration) {
            ph.spinning = static_cast<int>(ph.done);
            ph.drive_time = sp.t0 - spun;
            return ph;
        }
        spun += sp.duration;
        ++ph.done;
    }
    ph.drive_time = t - spun;
    return ph;
}

double RobotPath::heading_at(double s, double lo, double hi) const {
    Eigen::Vector2d dir =
        line_.point_at(std::min(s + 0.6, hi)) - line_.point_at(std::max(s - 0.6, lo));
    if (dir.norm() < 1e-6) dir = line_.tangent_at(s);
    return std::atan2(dir.y(), dir.x());
}

void RobotPath::init_file(const RouteConfig& config, const std::string& base_dir) {
    const std::string poses_path = resolve_path(config.poses_file, base_dir);
    const std::string times_path = resolve_path(config.times_file, base_dir);
    try {
        common::PoseList poses = common::read_kitti_poses(poses_path);
        if (config.times_file.empty())
            throw ScenarioError("route.times_file: needed with poses_file");
        times_ = common::read_times(times_path);
        if (config.camera_frame) {
            if (config.calib_file.empty()) {
                throw ScenarioError(
                    "route.calib_file: needed for camera-frame poses (or set camera_frame: false)");
            }
            const std::string calib = resolve_path(config.calib_file, base_dir);
            poses = common::camera_to_lidar_poses(poses, common::read_kitti_calib_tr(calib));
        }
        poses_ = std::move(poses);
    } catch (const common::IoError& e) {
        throw ScenarioError(std::string("route: ") + e.what());
    }
    if (poses_.size() < 2)
        throw ScenarioError("route: " + poses_path + " holds fewer than two poses");
    if (times_.size() != poses_.size()) {
        throw ScenarioError("route: " + times_path + " has " + std::to_string(times_.size()) +
                            " times for " + std::to_string(poses_.size()) + " poses");
    }
    for (std::size_t i = 1; i < times_.size(); ++i) {
        if (!(times_[i] > times_[i - 1]))
            throw ScenarioError("route: " + times_path + ": times do not increase at line " +
                                std::to_string(i + 1));
    }
    Points2 pts;
    for (const auto& T : poses_) {
        const Eigen::Vector2d p = T.translation().head<2>();
        if (pts.empty() || (p - pts.back()).norm() >= 1.0) pts.push_back(p);
    }
    if (pts.size() < 2)
        pts.push_back(poses_.back().translation().head<2>() + Eigen::Vector2d(1e-3, 0));
    line_ = Polyline(pts);
}

double RobotPath::duration() const {
    if (from_file()) return times_.back() - times_.front();
    double spun = 0.0;
    for (const Spin& sp : spins_) spun += sp.duration;
    return vertex_time_.back() + spun;
}

double RobotPath::arc_at(double t) const {
    if (from_file()) return line_.project(pose_at(t, Terrain(), 0).translation().head<2>());
    return arc_at_drive_time(phase(t).drive_time);
}

double RobotPath::arc_at_drive_time(double t) const {
    const auto it = std::upper_bound(vertex_time_.begin(), vertex_time_.end(), t);
    if (it == vertex_time_.begin()) return 0.0;
    if (it == vertex_time_.end()) return line_.length();
    const std::size_t j = static_cast<std::size_t>(it - vertex_time_.begin());
    const double f = (t - vertex_time_[j - 1]) / (vertex_time_[j] - vertex_time_[j - 1]);
    return line_.vertex_s(j - 1) + f * (line_.vertex_s(j) - line_.vertex_s(j - 1));
}

Eigen::Vector2d RobotPath::plan_position(double t) const {
    if (!from_file()) return line_.point_at(arc_at(t));
    const double ft = times_.front() + t;
    const auto it = std::upper_bound(times_.begin(), times_.end(), ft);
    if (it == times_.begin()) return poses_.front().translation().head<2>();
    if (it == times_.end()) return poses_.back().translation().head<2>();
    const std::size_t j = static_cast<std::size_t>(it - times_.begin());
    const double f = (ft - times_[j - 1]) / (times_[j] - times_[j - 1]);
    return ((1 - f) * poses_[j - 1].translation() + f * poses_[j].translation()).head<2>();
}

double RobotPath::waypoint_time(int i) const {
    if (from_file() || i < 0 || i >= num_waypoints()) return -1.0;
    const std::size_t v = waypoint_vertex_[static_cast<std::size_t>(i)];
    double spun = 0.0;
    for (const Spin& sp : spins_)
        if (sp.vertex < v) spun += sp.duration;
    return vertex_time_[v] + spun;
}

std::vector<double> RobotPath::scan_times(double t0, double t1, double rate) const {
    std::vector<double> out;
    if (from_file()) {
        const double base = times_.front();
        for (const double t : times_) {
            if (t - base >= t0 - 1e-9 && t - base <= t1 + 1e-9) out.push_back(t - base);
        }
        return out;
    }
    for (long k = 0;; ++k) {
        const double t = t0 + static_cast<double>(k) / rate;
        if (t > t1 + 1e-9) break;
        out.push_back(t);
    }
    return out;
}

std::vector<Eigen::Vector3d> RobotPath::ground_points(double height) const {
    std::vector<Eigen::Vector3d> out;
    for (const auto& T : poses_) {
        const Eigen::Vector3d g = T * Eigen::Vector3d(0, 0, -height);
        if (out.empty() || (g - out.back()).head<2>().norm() >= 2.0) out.push_back(g);
    }
    return out;
}

void RobotPath::drape(const Terrain& terrain, double height) {
    for (auto& T : poses_) {
        const Eigen::Vector3d g = T * Eigen::Vector3d(0, 0, -height);
        T.translation().z() += terrain.height(g.x(), g.y()) - g.z();
    }
}

Eigen::Isometry3d RobotPath::pose_at(double t, const Terrain& terrain, double height) const {
    if (from_file()) {
        const double ft = times_.front() + t;
        const auto it = std::upper_bound(times_.begin(), times_.end(), ft);
        if (it == times_.begin()) return poses_.front();
        if (it == times_.end()) return poses_.back();
        const std::size_t j = static_cast<std::size_t>(it - times_.begin());
        const double f = (ft - times_[j - 1]) / (times_[j] - times_[j - 1]);
        const Eigen::Quaterniond q0(poses_[j - 1].linear()), q1(poses_[j].linear());
        Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
        T.linear() = q0.slerp(f, q1).toRotationMatrix();
        T.translation() = (1 - f) * poses_[j - 1].translation() + f * poses_[j].translation();
        return T;
    }
    const Phase ph = phase(t);
    const double s = arc_at_drive_time(ph.drive_time);
    const Eigen::Vector2d p = line_.point_at(s);
    double yaw = 0.0;
    if (ph.spinning >= 0) {
        const Spin& sp = spins_[static_cast<std::size_t>(ph.spinning)];
        yaw = sp.yaw0 + sp.angle * (t - sp.t0) / sp.duration;
    } else {
        const double inf = std::numeric_limits<double>::infinity();
        yaw = heading_at(s, ph.done > 0 ? spins_[ph.done - 1].s : -inf,
                         ph.done < spins_.size() ? spins_[ph.done].s : inf);
    }
    const Eigen::Vector3d n = terrain.normal(p.x(), p.y());
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = (Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), n) *
                  Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()))
                     .toRotationMatrix();
    T.translation() = Eigen::Vector3d(p.x(), p.y(), terrain.height(p.x(), p.y())) + height * n;
    return T;
}

}  // namespace ltm::sim
