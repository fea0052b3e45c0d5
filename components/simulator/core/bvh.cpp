#include "simulator/core/bvh.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ltm::sim {
namespace {

constexpr int kBins = 16;
constexpr int kMaxDepth = 60;  // the traversal stack holds one node per level
constexpr std::uint32_t kMaxLeaf = 8;
constexpr float kTraversalCost = 1.0f;
constexpr float kTriangleCost = 1.5f;

float area(const Eigen::AlignedBox3f& b) {
    if (b.isEmpty()) return 0.0f;
    const Eigen::Vector3f d = b.sizes();
    return 2.0f * (d.x() * d.y() + d.y() * d.z() + d.z() * d.x());
}

}  // namespace

Bvh::Bvh(const Mesh& mesh) { build(mesh); }

Eigen::AlignedBox3f Bvh::bounds() const {
    if (nodes_.empty()) return {};
    const Node& n = nodes_[0];
    return {Eigen::Vector3f(n.lo[0], n.lo[1], n.lo[2]), Eigen::Vector3f(n.hi[0], n.hi[1], n.hi[2])};
}

void Bvh::build(const Mesh& mesh) {
    const std::size_t n = mesh.triangles.size();
    nodes_.clear();
    tris_.clear();
    ids_.clear();
    normals_.resize(n);
    if (n == 0) return;
    std::vector<Eigen::AlignedBox3f> boxes(n);
    std::vector<Eigen::Vector3f> centroids(n);
    std::vector<std::uint32_t> order(n);
    for (std::size_t i = 0; i < n; ++i) {
        const auto& t = mesh.triangles[i];
        const Eigen::Vector3f& a = mesh.vertices[t[0]];
        const Eigen::Vector3f& b = mesh.vertices[t[1]];
        const Eigen::Vector3f& c = mesh.vertices[t[2]];
        boxes[i] = Eigen::AlignedBox3f(a);
        boxes[i].extend(b);
        boxes[i].extend(c);
        centroids[i] = (a + b + c) / 3.0f;
        order[i] = static_cast<std::uint32_t>(i);
        const Eigen::Vector3f nrm = (b - a).cross(c - a);
        normals_[i] = nrm.norm() > 0 ? nrm.normalized() : Eigen::Vector3f::UnitZ();
    }
    nodes_.reserve(2 * n);
    nodes_.push_back(Node{{0, 0, 0}, 0, {0, 0, 0}, static_cast<std::uint32_t>(n)});
    subdivide(0, 0, boxes, centroids, order);
    ids_ = order;
    tris_.resize(n);
    for (std::size_t s = 0; s < n; ++s) {
        const auto& t = mesh.triangles[ids_[s]];
        const Eigen::Vector3f& a = mesh.vertices[t[0]];
        tris_[s] = Tri{a, mesh.vertices[t[1]] - a, mesh.vertices[t[2]] - a};
    }
    nodes_.shrink_to_fit();
}

// Recursion depth is bounded by the tree height (about 2 log2 n for SAH trees).
void Bvh::subdivide(std::uint32_t node_index, int depth, std::vector<Eigen::AlignedBox3f>& boxes,
                    std::vector<Eigen::Vector3f>& centroids, std::vector<std::uint32_t>& order) {
    const std::uint32_t first = nodes_[node_index].first, count = nodes_[node_index].count;
    Eigen::AlignedBox3f bounds, cbounds;
    for (std::uint32_t i = first; i < first + count; ++i) {
        bounds.extend(boxes[order[i]]);
        cbounds.extend(centroids[order[i]]);
    }
    for (int k = 0; k < 3; ++k) {
        nodes_[node_index].lo[k] = bounds.min()[k];
        nodes_[node_index].hi[k] = bounds.max()[k];
    }
    if (count <= 2 || depth >= kMaxDepth) return;

    // Binned SAH over the three axes.
    float best_cost = std::numeric_limits<float>::max();
    int best_axis = -1, best_split = 0;
    const Eigen::Vector3f extent = cbounds.sizes();
    for (int axis = 0; axis < 3; ++axis) {
        if (extent[axis] <= 0.0f) continue;
        Eigen::AlignedBox3f bin_box[kBins];
        std::uint32_t bin_count[kBins] = {};
        const float scale = kBins / extent[axis];
        for (std::uint32_t i = first; i < first + count; ++i) {
            const std::uint32_t id = order[i];
            const int b = std::min(
                kBins - 1, static_cast<int>((centroids[id][axis] - cbounds.min()[axis]) * scale));
            bin_box[b].extend(boxes[id]);
            ++bin_count[b];
        }
        float left_area[kBins - 1];
        std::uint32_t left_count[kBins - 1];
        Eigen::AlignedBox3f acc;
        std::uint32_t acc_count = 0;
        for (int b = 0; b < kBins - 1; ++b) {
            acc.extend(bin_box[b]);
            acc_count += bin_count[b];
            left_area[b] = area(acc);
            left_count[b] = acc_count;
        }
        acc.setEmpty();
        acc_count = 0;
        for (int b = kBins - 1; b > 0; --b) {
            acc.extend(bin_box[b]);
            acc_count += bin_count[b];
            const float cost = left_area[b - 1] * left_count[b - 1] + area(acc) * acc_count;
            if (left_count[b - 1] > 0 && acc_count > 0 && cost < best_cost) {
                best_cost = cost;
                best_axis = axis;
                best_split = b;
            }
        }
    }
    const float leaf_cost = kTriangleCost * count;
    const float split_cost =
        kTraversalCost + kTriangleCost * best_cost / std::max(area(bounds), 1e-12f);
    if (best_axis < 0 || (split_cost >= leaf_cost && count <= kMaxLeaf)) return;

    const float scale = kBins / extent[best_axis];
    const float cmin = cbounds.min()[best_axis];
    auto mid_it =
        std::partition(order.begin() + first, order.begin() + first + count, [&](std::uint32_t id) {
            const int b =
                std::min(kBins - 1, static_cast<int>((centroids[id][best_axis] - cmin) * scale));
            return b < best_split;
        });
    std::uint32_t left_count = static_cast<std::uint32_t>(mid_it - (order.begin() + first));
    if (left_count == 0 || left_count == count) left_count = count / 2;  // degenerate: halve

    const std::uint32_t left = static_cast<std::uint32_t>(nodes_.size());
    nodes_.push_back(Node{{0, 0, 0}, first, {0, 0, 0}, left_count});
    nodes_.push_back(Node{{0, 0, 0}, first + left_count, {0, 0, 0}, count - left_count});
    nodes_[node_index].first = left;
    nodes_[node_index].count = 0;
    subdivide(left, depth + 1, boxes, centroids, order);
    subdivide(left + 1, depth + 1, boxes, centroids, order);
}

bool Bvh::intersect(const Eigen::Vector3f& origin, const Eigen::Vector3f& dir, float tmin,
                    float tmax, RayHit& hit) const {
    if (nodes_.empty()) return false;
    float inv[3];
    for (int k = 0; k < 3; ++k) {
        inv[k] = std::abs(dir[k]) > 1e-20f ? 1.0f / dir[k] : std::copysign(1e30f, dir[k]);
    }
    const float o[3] = {origin.x(), origin.y(), origin.z()};
    float best = tmax;
    bool found = false;

    auto enter = [&](const Node& n) {
        float t0 = tmin, t1 = best;
        for (int k = 0; k < 3; ++k) {
            float a = (n.lo[k] - o[k]) * inv[k];
            float b = (n.hi[k] - o[k]) * inv[k];
            if (a > b) std::swap(a, b);
            t0 = a > t0 ? a : t0;
            t1 = b < t1 ? b : t1;
        }
        return t0 <= t1 ? t0 : std::numeric_limits<float>::infinity();
    };

    std::uint32_t stack[64];
    int top = 0;
    std::uint32_t current = 0;
    if (enter(nodes_[0]) == std::numeric_limits<float>::infinity()) return false;
    while (true) {
        const Node& n = nodes_[current];
        if (n.count > 0) {
            for (std::uint32_t s = n.first; s < n.first + n.count; ++s) {
                const Tri& tri = tris_[s];
                const Eigen::Vector3f p = dir.cross(tri.e2);
                const float det = tri.e1.dot(p);
                if (std::abs(det) < 1e-14f) continue;
                const float inv_det = 1.0f / det;
                const Eigen::Vector3f sv = origin - tri.v0;
                const float u = sv.dot(p) * inv_det;
                if (u < 0.0f || u > 1.0f) continue;
                const Eigen::Vector3f q = sv.cross(tri.e1);
                const float v = dir.dot(q) * inv_det;
                if (v < 0.0f || u + v > 1.0f) continue;
                const float t = tri.e2.dot(q) * inv_det;
                if (t > tmin && t < best) {
                    best = t;
                    hit.t = t;
                    hit.triangle = ids_[s];
                    found = true;
                }
            }
        } else {
            std::uint32_t near = n.first, far = n.first + 1;
            float d_near = enter(nodes_[near]), d_far = enter(nodes_[far]);
            if (d_far < d_near) {
                std::swap(near, far);
                std::swap(d_near, d_far);
            }
            if (d_near != std::numeric_limits<float>::infinity()) {
                if (d_far != std::numeric_limits<float>::infinity()) stack[top++] = far;
                current = near;
                continue;
            }
        }
        // Pop the next node still worth visiting.
        bool next = false;
        while (top > 0) {
            current = stack[--top];
            if (enter(nodes_[current]) != std::numeric_limits<float>::infinity()) {
                next = true;
                break;
            }
        }
        if (!next) return found;
    }
}

}  // namespace ltm::sim
