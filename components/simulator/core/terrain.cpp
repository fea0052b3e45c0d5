#include "simulator/core/terrain.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

#include "simulator/core/random.hpp"

namespace ltm::sim {
namespace {

double smoothstep(double e0, double e1, double x) {
    const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
    return t * t * (3 - 2 * t);
}

}  // namespace

Terrain::Terrain(const TerrainConfig& config, const Eigen::AlignedBox2d& region, std::uint64_t seed)
    : config_(config), region_(region) {
    nx_ = std::max(2, static_cast<int>(std::ceil(region.sizes().x() / config.cell)) + 1);
    ny_ = std::max(2, static_cast<int>(std::ceil(region.sizes().y() / config.cell)) + 1);
    region_.max() =
        region_.min() + Eigen::Vector2d((nx_ - 1) * config.cell, (ny_ - 1) * config.cell);
    // Three plane waves of decreasing wavelength and amplitude, random directions and phases.
    Rng rng(hash_mix(seed, 0x7E44A1));
    struct Wave {
        Eigen::Vector2d k;
        double phase, amp;
    };
    Wave waves[3];
    const double ratios[3] = {1.0, 1.0 / 1.7, 1.0 / 2.9}, amps[3] = {1.0, 0.5, 0.25};
    for (int w = 0; w < 3; ++w) {
        const double dir = rng.uniform(0, 2 * M_PI);
        const double len = std::max(config.wavelength, 1.0) * ratios[w];
        waves[w] = {Eigen::Vector2d(std::cos(dir), std::sin(dir)) * (2 * M_PI / len),
                    rng.uniform(0, 2 * M_PI), amps[w] / 1.75 * config.amplitude};
    }
    heights_.resize(static_cast<std::size_t>(nx_) * ny_);
    for (int j = 0; j < ny_; ++j) {
        for (int i = 0; i < nx_; ++i) {
            const Eigen::Vector2d p = vertex_xy(i, j);
            double h = 0;
            for (const auto& w : waves) h += w.amp * std::sin(w.k.dot(p) + w.phase);
            heights_[static_cast<std::size_t>(j) * nx_ + i] = static_cast<float>(h);
        }
    }
    keep_.assign(static_cast<std::size_t>(nx_ - 1) * (ny_ - 1), 1);
}

Eigen::Vector2d Terrain::vertex_xy(int i, int j) const {
    return region_.min() + Eigen::Vector2d(i * config_.cell, j * config_.cell);
}

void Terrain::anchor(const std::vector<Eigen::Vector3d>& ground, double radius) {
    if (ground.empty()) return;
    const double bucket = radius / 2;
    auto key = [&](int ix, int iy) {
        return (static_cast<std::int64_t>(ix) << 32) ^ static_cast<std::uint32_t>(iy);
    };
    std::unordered_map<std::int64_t, std::vector<int>> grid;
    for (std::size_t k = 0; k < ground.size(); ++k) {
        grid[key(int(std::floor(ground[k].x() / bucket)), int(std::floor(ground[k].y() / bucket)))]
            .push_back(static_cast<int>(k));
    }
    for (int j = 0; j < ny_; ++j) {
        for (int i = 0; i < nx_; ++i) {
            const Eigen::Vector2d p = vertex_xy(i, j);
            const int cx = int(std::floor(p.x() / bucket)), cy = int(std::floor(p.y() / bucket));
            double wsum = 0, hsum = 0, nearest = std::numeric_limits<double>::max(), nearest_z = 0;
            // Rings of buckets until something is found (at least the radius).
            for (int ring = 0; ring < 64; ++ring) {
                for (int dx = -ring; dx <= ring; ++dx) {
                    for (int dy = -ring; dy <= ring; ++dy) {
                        if (std::max(std::abs(dx), std::abs(dy)) != ring) continue;
                        const auto it = grid.find(key(cx + dx, cy + dy));
                        if (it == grid.end()) continue;
                        for (const int k : it->second) {
                            const double d2 = (ground[k].head<2>() - p).squaredNorm();
                            if (d2 < nearest) {
                                nearest = d2;
                                nearest_z = ground[k].z();
                            }
                            if (d2 < radius * radius) {
                                const double w = 1.0 / (d2 + 1.0);
                                wsum += w;
                                hsum += w * ground[k].z();
                            }
                        }
                    }
                }
                if (ring >= 2 && nearest < std::numeric_limits<double>::max()) break;
            }
            const double d = std::sqrt(nearest);
            const double base = wsum > 0 ? hsum / wsum : nearest_z;
            float& h = heights_[static_cast<std::size_t>(j) * nx_ + i];
            h = static_cast<float>(base + h * smoothstep(6.0, radius, d));
        }
    }
}

void Terrain::restrict_to(const Points2& samples, double radius) {
    std::fill(keep_.begin(), keep_.end(), 0);
    const int r = static_cast<int>(std::ceil(radius / config_.cell));
    for (const auto& s : samples) {
        const int ci = static_cast<int>((s.x() - region_.min().x()) / config_.cell);
        const int cj = static_cast<int>((s.y() - region_.min().y()) / config_.cell);
        for (int j = std::max(0, cj - r); j <= std::min(ny_ - 2, cj + r); ++j) {
            for (int i = std::max(0, ci - r); i <= std::min(nx_ - 2, ci + r); ++i) {
                if ((i - ci) * (i - ci) + (j - cj) * (j - cj) <= r * r) {
                    keep_[static_cast<std::size_t>(j) * (nx_ - 1) + i] = 1;
                }
            }
        }
    }
}

bool Terrain::covered(double x, double y) const {
    if (keep_.empty()) return false;
    const int i = static_cast<int>(std::floor((x - region_.min().x()) / config_.cell));
    const int j = static_cast<int>(std::floor((y - region_.min().y()) / config_.cell));
    if (i < 0 || j < 0 || i >= nx_ - 1 || j >= ny_ - 1) return false;
    return keep_[static_cast<std::size_t>(j) * (nx_ - 1) + i] != 0;
}

double Terrain::height(double x, double y) const {
    const double gx = std::clamp((x - region_.min().x()) / config_.cell, 0.0, nx_ - 1.0);
    const double gy = std::clamp((y - region_.min().y()) / config_.cell, 0.0, ny_ - 1.0);
    const int i = std::min(static_cast<int>(gx), nx_ - 2),
              j = std::min(static_cast<int>(gy), ny_ - 2);
    const double fx = gx - i, fy = gy - j;
    // Cells split along the diagonal from (i+1, j) to (i, j+1), as append_mesh triangulates.
    if (fx + fy <= 1.0) {
        return at(i, j) + fx * (at(i + 1, j) - at(i, j)) + fy * (at(i, j + 1) - at(i, j));
    }
    return at(i + 1, j + 1) + (1 - fx) * (at(i, j + 1) - at(i + 1, j + 1)) +
           (1 - fy) * (at(i + 1, j) - at(i + 1, j + 1));
}

Eigen::Vector3d Terrain::normal(double x, double y) const {
    const double d = config_.cell;
    const double gx = (height(x + d, y) - height(x - d, y)) / (2 * d);
    const double gy = (height(x, y + d) - height(x, y - d)) / (2 * d);
    return Eigen::Vector3d(-gx, -gy, 1.0).normalized();
}

Eigen::Vector2d Terrain::height_range(const OrientedRect& r) const {
    double lo = std::numeric_limits<double>::max(), hi = std::numeric_limits<double>::lowest();
    const int n = 4;
    for (int a = 0; a <= n; ++a) {
        for (int b = 0; b <= n; ++b) {
            const Eigen::Vector2d p = r.center + (2.0 * a / n - 1) * r.half.x() * r.axis_x() +
                                      (2.0 * b / n - 1) * r.half.y() * r.axis_y();
            const double h = height(p.x(), p.y());
            lo = std::min(lo, h);
            hi = std::max(hi, h);
        }
    }
    return {lo, hi};
}

void Terrain::append_mesh(Mesh& mesh,
                          const std::function<Material(const Eigen::Vector2d&)>& material) const {
    std::vector<int> index(heights_.size(), -1);
    auto vid = [&](int i, int j) {
        int& id = index[static_cast<std::size_t>(j) * nx_ + i];
        if (id < 0) {
            const Eigen::Vector2d p = vertex_xy(i, j);
            mesh.vertices.emplace_back(float(p.x()), float(p.y()), float(at(i, j)));
            id = static_cast<int>(mesh.vertices.size()) - 1;
        }
        return id;
    };
    for (int j = 0; j + 1 < ny_; ++j) {
        for (int i = 0; i + 1 < nx_; ++i) {
            if (!keep_[static_cast<std::size_t>(j) * (nx_ - 1) + i]) continue;
            const int v00 = vid(i, j), v10 = vid(i + 1, j), v01 = vid(i, j + 1),
                      v11 = vid(i + 1, j + 1);
            const Eigen::Vector2d c =
                vertex_xy(i, j) + Eigen::Vector2d::Constant(0.5 * config_.cell);
            const Eigen::Vector2d third = Eigen::Vector2d::Constant(config_.cell / 6);
            mesh.triangles.emplace_back(v00, v10, v01);
            mesh.material.push_back(material(c - third));
            mesh.triangles.emplace_back(v10, v11, v01);
            mesh.material.push_back(material(c + third));
            mesh.object.push_back(0);
            mesh.object.push_back(0);
        }
    }
}

}  // namespace ltm::sim
