#pragma once
// Deterministic randomness: a counter-based hash for per-ray draws (independent of evaluation
// order, so scan(i) is a pure function of the seed and i) and a small sequential generator for
// procedural layouts. Never std::*_distribution: their output differs between standard libraries.
#include <cmath>
#include <cstdint>

namespace ltm::sim {

inline std::uint64_t splitmix64(std::uint64_t x) {
    x += 0x9E3779B97F4A7C15ull;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    return x ^ (x >> 31);
}

// Hash of a tuple of integers (order matters).
inline std::uint64_t hash_mix(std::uint64_t a, std::uint64_t b) {
    return splitmix64(a ^ (splitmix64(b) + 0x632BE59BD9B4E019ull + (a << 6) + (a >> 2)));
}
inline std::uint64_t hash_mix(std::uint64_t a, std::uint64_t b, std::uint64_t c) {
    return hash_mix(hash_mix(a, b), c);
}
inline std::uint64_t hash_mix(std::uint64_t a, std::uint64_t b, std::uint64_t c, std::uint64_t d) {
    return hash_mix(hash_mix(hash_mix(a, b), c), d);
}

// Uniform in [0, 1) from the top 53 bits of a hash.
inline double hash_unit(std::uint64_t h) { return static_cast<double>(h >> 11) * 0x1.0p-53; }

// Standard normal from a hash (Box-Muller on two derived uniforms).
inline double hash_normal(std::uint64_t h) {
    const double u1 = hash_unit(splitmix64(h)) + 0x1.0p-54;
    const double u2 = hash_unit(splitmix64(h ^ 0xA5A5A5A5A5A5A5A5ull));
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
}

// Cheap near-normal (mean 0, sigma 1, bounded by +-3.46) from a hash: the sum of four 16-bit
// uniforms (Irwin-Hall). For secondary noise where tails do not matter (intensity).
inline double hash_normal_fast(std::uint64_t h) {
    h = splitmix64(h);
    double sum = 0.0;
    for (int k = 0; k < 4; ++k) sum += static_cast<double>((h >> (16 * k)) & 0xFFFF) / 65536.0;
    return (sum - 2.0) * 1.7320508075688772;
}

// Sequential generator for layouts: every call advances the state.
class Rng {
  public:
    explicit Rng(std::uint64_t seed) : state_(splitmix64(seed)) {}
    std::uint64_t next() { return splitmix64(state_++); }
    double uniform() { return hash_unit(next()); }
    double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
    // Integer in [lo, hi] (inclusive).
    int uniform_int(int lo, int hi) {
        return lo + static_cast<int>(uniform() * static_cast<double>(hi - lo + 1));
    }
    double normal() { return hash_normal(next()); }
    bool chance(double p) { return uniform() < p; }

  private:
    std::uint64_t state_;
};

}  // namespace ltm::sim
