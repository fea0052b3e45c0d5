#include "registration/core/imls.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>

namespace ltm::registration {
namespace {

// exp(x) for x <= 0 to about 1e-4 relative (2^(x log2 e): exponent bits plus a cubic for the
// fraction); the weights need no more, and std::exp was a tenth of the registration time.
inline float fast_exp_neg(float x) {
    if (x < -80.0f) return 0.0f;
    const float y = x * 1.44269504f;  // log2(e)
    // floor(y) by truncation (|y| < 116 here: exact), a few instructions instead of std::floor's
    // dozen without SSE4.1.
    const std::int32_t t = std::int32_t(y);
    const float fi = float(t - std::int32_t(float(t) > y));
    const float f = y - fi;                                                       // [0, 1)
    const float p = 1.0f + f * (0.6951786f + f * (0.2261237f + f * 0.0781523f));  // 2^f
    std::int32_t bits;
    std::memcpy(&bits, &p, sizeof bits);
    bits += std::int32_t(fi) << 23;
    float out;
    std::memcpy(&out, &bits, sizeof out);
    return out;
}

}  // namespace

int usable_neighbours(const VoxelGrid& grid, const Eigen::Vector3f& x, std::uint32_t* out) {
    return grid.usable_neighbours(x, out);
}

bool imls_from_neighbours(const std::vector<Surfel>& surfels, const std::uint32_t* found, int n,
                          const Eigen::Vector3f& x, const ImlsParams& params, ImlsResult* result) {
    // The nearest centre within max_distance (the first of equals), selected without branches:
    // which neighbour is nearest is as good as random, and its mispredictions were a large part
    // of the cost.
    std::uint32_t nearest = 0;
    const float reach = params.max_distance * params.max_distance;
    float best = reach;
    for (int k = 0; k < n; ++k) {
        const float d2 = (x - surfels[found[k]].centre).squaredNorm();
        const bool closer = d2 < best;
        nearest = closer ? found[k] : nearest;
        best = closer ? d2 : best;
    }
    if (!(best < reach)) return false;
    const Eigen::Vector3f& nx = surfels[nearest].normal;
    const float inv_h2 = 1.0f / (params.bandwidth * params.bandwidth);
    float num = 0.0f, den = 0.0f;
    int used = 0;
    for (int k = 0; k < n; ++k) {
        const Surfel& s = surfels[found[k]];
        const float agreement = s.normal.dot(nx);
        if (std::abs(agreement) < params.min_normal_agreement) continue;
        const Eigen::Vector3f d = x - s.centre;
        const float w = fast_exp_neg(-d.squaredNorm() * inv_h2);
        const float signed_distance = d.dot(s.normal);
        num += agreement >= 0.0f ? w * signed_distance : -w * signed_distance;
        den += w;
        ++used;
    }
    if (!(den > 0.0f)) return false;
    result->distance = num / den;
    result->normal = nx;
    result->projection = x - result->distance * nx;
    result->stability = surfels[nearest].stability;
    result->nearest = nearest;
    result->neighbours = used;
    return true;
}

bool imls_distance(const VoxelGrid& grid, const Eigen::Vector3f& x, const ImlsParams& params,
                   ImlsResult* result) {
    std::uint32_t found[27];
    const int n = usable_neighbours(grid, x, found);
    return imls_from_neighbours(grid.surfels(), found, n, x, params, result);
}

}  // namespace ltm::registration
