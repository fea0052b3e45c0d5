#pragma once
// SITE/anchor.yaml: the site's own coordinates (frame `site`: a survey grid, a plant's drawing)
// against the map frame, p_site = T_site_map * p_map. Given as a transform, or fitted to a few
// surveyed points (map xyz -> site xyz, at least 3, not on one line: Umeyama without scale, the
// map's metres are metres). The map frame stays put from version to version, so one anchor holds
// for every version of the site. The file (written by ltm_site anchor, read by the localisation):
//   # ltm site anchor: p_site = R * p_map + t
//   translation: [x, y, z]
//   rotation_xyzw: [qx, qy, qz, qw]
//   source: points|transform
//   points: N            rms_m: R            max_m: M     (residuals of the fit; 0 for a transform)
#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

namespace ltm::map {

struct SiteAnchor {
    Eigen::Isometry3d T_site_map = Eigen::Isometry3d::Identity();
    std::string source = "transform";  // or "points"
    std::size_t points = 0;
    double rms_m = 0.0, max_m = 0.0;  // the fit's residuals [m]
    EIGEN_MAKE_ALIGNED_OPERATOR_NEW
};

std::string anchor_file(const std::string& site_dir);  // SITE/anchor.yaml

// roll, pitch, yaw in degrees (R = Rz(yaw) Ry(pitch) Rx(roll)).
SiteAnchor anchor_from_transform(const Eigen::Vector3d& t, double roll_deg, double pitch_deg,
                                 double yaw_deg);
// Throws std::invalid_argument (one line) with fewer than 3 pairs, sizes that differ, or points
// (nearly) on one line.
SiteAnchor fit_anchor(const std::vector<Eigen::Vector3d>& map_xyz,
                      const std::vector<Eigen::Vector3d>& site_xyz);
// A points file: one pair a line, "map_x map_y map_z site_x site_y site_z"; '#' starts a comment.
// Throws common::FormatError naming the line.
void read_survey_points(const std::string& path, std::vector<Eigen::Vector3d>* map_xyz,
                        std::vector<Eigen::Vector3d>* site_xyz);

void write_anchor(const std::string& site_dir, const SiteAnchor& anchor);  // atomic
// nullopt when the site has no anchor.yaml; throws common::FormatError (one line, naming the
// line) when it cannot be read as one.
std::optional<SiteAnchor> read_anchor(const std::string& site_dir);

}  // namespace ltm::map
