#pragma once
// Scan Context place descriptors (Kim & Kim 2018; METHOD.md sections 3 and 6): a polar grid of
// rings (range) x sectors (azimuth) around the sensor, in the sensor's horizontal plane.
//   kMaxHeight:    each bin holds the maximum z of its points (plus the sensor height), compared
//                  column by column with the cosine distance (the loop-closure descriptor);
//   kMeanVariance: ScanContext++ as METHOD.md section 6 defines it: each bin holds the mean and
//                  the standard deviation of the z of its points, compared bin by bin with the
//                  2-Wasserstein distance of two 1-D Gaussians (global localisation reuses it).
// Both are compared under every column shift; the best shift gives the yaw between the scans.
// The ring key (per ring, the mean over sectors) is yaw-invariant: it indexes the k-d tree.
#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common/core/config_check.hpp"

namespace ltm::places {

enum class ScanContextKind : std::uint8_t { kMaxHeight = 0, kMeanVariance = 1 };

struct ScanContextConfig {
    ScanContextKind kind = ScanContextKind::kMaxHeight;
    int rings = 20;
    int sectors = 60;
    double max_range = 80.0;     // points farther (horizontally) are left out [m]
    double min_range = 0.0;      // points closer are left out [m]
    double sensor_height = 2.0;  // added to z so that the ground is about 0 (KITTI: 1.73 m) [m]
    // ScanContext++ only: a bin occupied in one scan and empty in the other costs this (the
    // squared distance, [m^2]); a pair of occupied bins costs min(W2^2, this).
    double empty_bin_cost = 4.0;
    // Shifts tried: all of them (0), or only this many sectors either side of the shift that
    // aligns the sector keys best (the Scan Context paper's fast search).
    int shift_search_radius = 0;
};

// Calls v(key, field, rule) for every field but the kind (an enum: loaders read it as a name), keys
// under `prefix` ("scan_context."); the rule is the field's (common/core/config_check.hpp).
template <class Visitor>
void visit_fields(ScanContextConfig& c, const std::string& prefix, Visitor&& v) {
    using namespace common::rules;
    v(prefix + "rings", c.rings, in_range(1, 1000));
    v(prefix + "sectors", c.sectors, in_range(4, 3600));
    v(prefix + "max_range", c.max_range, positive);
    v(prefix + "min_range", c.min_range, non_negative);  // and < max_range
    v(prefix + "sensor_height", c.sensor_height, finite);
    v(prefix + "empty_bin_cost", c.empty_bin_cost, positive.or_infinite());
    v(prefix + "shift_search_radius", c.shift_search_radius, non_negative);
}

// The first field that breaks its rule, then the rules across fields (and the kind); keys relative
// ("rings"). nullopt when valid.
std::optional<common::ConfigProblem> validate(const ScanContextConfig& config);

struct ScanContext {
    ScanContextKind kind = ScanContextKind::kMaxHeight;
    int rings = 0, sectors = 0;
    // Row-major rings x sectors: value(r, s) = value[r * sectors + s].
    std::vector<float> value;            // max height, or mean height (kMeanVariance) [m]
    std::vector<float> spread;           // kMeanVariance: standard deviation of z; else empty [m]
    std::vector<std::uint8_t> occupied;  // 1 where the bin has points

    bool empty() const { return value.empty(); }
    float at(int ring, int sector) const { return value[std::size_t(ring) * sectors + sector]; }
    // What its bins take (bytes).
    std::size_t memory_bytes() const {
        return (value.capacity() + spread.capacity()) * sizeof(float) + occupied.capacity();
    }
};

// The descriptor of a scan (points in the sensor frame, z up). Non-finite points are skipped.
ScanContext make_scan_context(const std::vector<Eigen::Vector3f>& points,
                              const ScanContextConfig& config);

// Per ring, the mean of value over all sectors (yaw-invariant) [rings].
Eigen::VectorXf ring_key(const ScanContext& sc);
// Per sector, the mean of value over all rings [sectors].
Eigen::VectorXf sector_key(const ScanContext& sc);

struct ScanContextMatch {
    double distance = 1.0;  // kMaxHeight: 0 (same) .. 1 (unrelated); kMeanVariance: [m^2]
    int shift = 0;          // sectors: query column j matches candidate column (j + shift)
    double yaw = 0.0;       // rotation of the query sensor relative to the candidate's, about z:
                            // R_candidate_query = Rz(yaw) [rad], in (-pi, pi]
    bool valid = false;     // false: the descriptors do not share a shape or kind, or are empty
};

// Best column shift between two descriptors of the same kind and shape (the config gives the
// shift search radius and the empty-bin cost; its other fields are not used).
ScanContextMatch compare(const ScanContext& query, const ScanContext& candidate,
                         const ScanContextConfig& config);

// The distance at one given shift (as defined for ScanContextMatch::shift); infinity when the
// descriptors are not comparable.
double distance_at_shift(const ScanContext& query, const ScanContext& candidate, int shift,
                         const ScanContextConfig& config);

}  // namespace ltm::places
