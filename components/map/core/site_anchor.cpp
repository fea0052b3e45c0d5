#include "map/core/site_anchor.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "common/core/file_io.hpp"
#include "common/core/io_error.hpp"

namespace ltm::map {
namespace {

namespace fs = std::filesystem;

constexpr double kDegToRad = M_PI / 180.0;
// The second singular value of the centred points over the first: below, the points are on a line
// and the rotation about it is not determined.
constexpr double kMinSpread = 1e-3;

// "[a, b, c]" -> numbers; false when it is not a list of `n` finite numbers.
bool parse_list(std::string text, std::size_t n, double* out) {
    if (text.size() < 2 || text.front() != '[' || text.back() != ']') return false;
    text = text.substr(1, text.size() - 2);
    std::istringstream in(text);
    std::string item;
    std::size_t k = 0;
    while (std::getline(in, item, ',')) {
        if (k >= n) return false;
        char* end = nullptr;
        out[k] = std::strtod(item.c_str(), &end);
        while (end && *end == ' ') ++end;
        if (end == item.c_str() || (end && *end != '\0') || !std::isfinite(out[k])) return false;
        ++k;
    }
    return k == n;
}

}  // namespace

std::string anchor_file(const std::string& site_dir) {
    return (fs::path(site_dir) / "anchor.yaml").string();
}

SiteAnchor anchor_from_transform(const Eigen::Vector3d& t, double roll_deg, double pitch_deg,
                                 double yaw_deg) {
    SiteAnchor a;
    a.T_site_map.linear() = (Eigen::AngleAxisd(yaw_deg * kDegToRad, Eigen::Vector3d::UnitZ()) *
                             Eigen::AngleAxisd(pitch_deg * kDegToRad, Eigen::Vector3d::UnitY()) *
                             Eigen::AngleAxisd(roll_deg * kDegToRad, Eigen::Vector3d::UnitX()))
                                .toRotationMatrix();
    a.T_site_map.translation() = t;
    a.source = "transform";
    return a;
}

SiteAnchor fit_anchor(const std::vector<Eigen::Vector3d>& map_xyz,
                      const std::vector<Eigen::Vector3d>& site_xyz) {
    if (map_xyz.size() != site_xyz.size())
        throw std::invalid_argument("anchor: " + std::to_string(map_xyz.size()) +
                                    " map points but " + std::to_string(site_xyz.size()) +
                                    " site points");
    const std::size_t n = map_xyz.size();
    if (n < 3)
        throw std::invalid_argument("anchor: " + std::to_string(n) +
                                    " surveyed points; at least 3 (not on one line) are needed");
    Eigen::Matrix3Xd src(3, n), dst(3, n);
    for (std::size_t i = 0; i < n; ++i) {
        src.col(Eigen::Index(i)) = map_xyz[i];
        dst.col(Eigen::Index(i)) = site_xyz[i];
    }
    const Eigen::Matrix3Xd centred = src.colwise() - src.rowwise().mean();
    const Eigen::JacobiSVD<Eigen::Matrix3Xd> svd(centred);
    const Eigen::Vector3d s = svd.singularValues();
    if (!(s(0) > 0) || s(1) < kMinSpread * s(0))
        throw std::invalid_argument(
            "anchor: the surveyed points are (nearly) on one line: the rotation about it is not "
            "determined; add a point off that line");
    SiteAnchor a;
    a.T_site_map.matrix() = Eigen::umeyama(src, dst, false);
    a.source = "points";
    a.points = n;
    double sum = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        const double r = (a.T_site_map * map_xyz[i] - site_xyz[i]).norm();
        sum += r * r;
        a.max_m = std::max(a.max_m, r);
    }
    a.rms_m = std::sqrt(sum / double(n));
    return a;
}

void read_survey_points(const std::string& path, std::vector<Eigen::Vector3d>* map_xyz,
                        std::vector<Eigen::Vector3d>* site_xyz) {
    const std::string text = common::read_file(path, path);
    std::istringstream in(text);
    std::string line;
    int number = 0;
    std::uint64_t offset = 0;
    while (std::getline(in, line)) {
        ++number;
        const std::uint64_t at = offset;
        offset += line.size() + 1;
        const std::string data = line.substr(0, line.find('#'));
        std::istringstream fields(data);
        double v[6];
        int k = 0;
        while (k < 6 && fields >> v[k]) ++k;
        std::string rest;
        if (k == 0 && !(fields.clear(), fields >> rest)) continue;  // blank or comment
        fields.clear();
        if (k != 6 || (fields >> rest) || !std::isfinite(v[0] + v[1] + v[2] + v[3] + v[4] + v[5]))
            throw common::FormatError(path, "line " + std::to_string(number), at,
                                      "expected 6 numbers: map x y z, site x y z");
        map_xyz->emplace_back(v[0], v[1], v[2]);
        site_xyz->emplace_back(v[3], v[4], v[5]);
    }
}

void write_anchor(const std::string& site_dir, const SiteAnchor& a) {
    const Eigen::Quaterniond q(a.T_site_map.rotation());
    const Eigen::Vector3d t = a.T_site_map.translation();
    char buf[600];
    std::snprintf(buf, sizeof buf,
                  "# ltm site anchor: p_site = R * p_map + t (components/site/README.md)\n"
                  "translation: [%.6f, %.6f, %.6f]\n"
                  "rotation_xyzw: [%.12f, %.12f, %.12f, %.12f]\n"
                  "source: %s\npoints: %zu\nrms_m: %.6f\nmax_m: %.6f\n",
                  t.x(), t.y(), t.z(), q.x(), q.y(), q.z(), q.w(), a.source.c_str(), a.points,
                  a.rms_m, a.max_m);
    fs::create_directories(site_dir);
    common::write_file_atomic(anchor_file(site_dir), std::string(buf));
}

std::optional<SiteAnchor> read_anchor(const std::string& site_dir) {
    const std::string path = anchor_file(site_dir);
    std::error_code ec;
    if (!fs::exists(path, ec)) return std::nullopt;
    const std::string text = common::read_file(path, path);
    std::istringstream in(text);
    std::string line;
    int number = 0;
    std::uint64_t offset = 0;
    bool has_t = false, has_q = false;
    double t[3] = {}, q[4] = {};
    SiteAnchor a;
    while (std::getline(in, line)) {
        ++number;
        const std::uint64_t at = offset;
        offset += line.size() + 1;
        const std::string data = line.substr(0, line.find('#'));
        if (data.find_first_not_of(" \t\r") == std::string::npos) continue;
        const auto colon = data.find(':');
        const std::string key = colon == std::string::npos ? data : data.substr(0, colon);
        std::string value = colon == std::string::npos ? "" : data.substr(colon + 1);
        value.erase(0, value.find_first_not_of(' '));
        value.erase(value.find_last_not_of(" \r") + 1);
        auto fail = [&](const std::string& problem) {
            throw common::FormatError(path, "line " + std::to_string(number), at, problem);
        };
        char* end = nullptr;
        if (key == "translation") {
            if (!parse_list(value, 3, t)) fail("translation: expected [x, y, z]");
            has_t = true;
        } else if (key == "rotation_xyzw") {
            if (!parse_list(value, 4, q)) fail("rotation_xyzw: expected [qx, qy, qz, qw]");
            has_q = true;
        } else if (key == "source") {
            if (value != "points" && value != "transform") fail("source: points or transform");
            a.source = value;
        } else if (key == "points") {
            a.points = std::size_t(std::strtoull(value.c_str(), &end, 10));
            if (value.empty() || *end != '\0') fail("points: expected a count");
        } else if (key == "rms_m" || key == "max_m") {
            const double v = std::strtod(value.c_str(), &end);
            if (value.empty() || *end != '\0' || !std::isfinite(v)) fail(key + ": expected metres");
            (key == "rms_m" ? a.rms_m : a.max_m) = v;
        } else {
            fail("unknown key '" + key +
                 "' (known: translation, rotation_xyzw, source, points, rms_m, max_m)");
        }
    }
    if (!has_t || !has_q) throw common::FormatError(path, "needs translation and rotation_xyzw");
    const Eigen::Quaterniond quat(q[3], q[0], q[1], q[2]);
    if (std::abs(quat.norm() - 1.0) > 1e-6)
        throw common::FormatError(path, "rotation_xyzw is not a unit quaternion");
    a.T_site_map = Eigen::Isometry3d::Identity();
    a.T_site_map.linear() = quat.normalized().toRotationMatrix();
    a.T_site_map.translation() = Eigen::Vector3d(t[0], t[1], t[2]);
    return a;
}

}  // namespace ltm::map
