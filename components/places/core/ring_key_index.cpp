#include "places/core/ring_key_index.hpp"

#include <algorithm>
#include <cmath>
#include <nanoflann.hpp>

namespace ltm::places {

// nanoflann reads the keys through this adaptor; its size is frozen at build time.
struct RingKeyIndex::Tree {
    struct Adaptor {
        const std::vector<float>* keys;
        std::size_t count;
        int dim;
        std::size_t kdtree_get_point_count() const { return count; }
        float kdtree_get_pt(std::size_t i, std::size_t d) const {
            return (*keys)[i * std::size_t(dim) + d];
        }
        template <class BBox>
        bool kdtree_get_bbox(BBox&) const {
            return false;
        }
    };
    using Index = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, Adaptor>,
                                                      Adaptor, -1, std::uint32_t>;
    Adaptor adaptor;
    Index index;
    Tree(const std::vector<float>* keys, std::size_t count, int dim)
        : adaptor{keys, count, dim},
          index(dim, adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(10)) {}
};

RingKeyIndex::RingKeyIndex(int dim, std::size_t rebuild_every)
    : dim_(std::max(1, dim)), rebuild_every_(std::max<std::size_t>(1, rebuild_every)) {}
RingKeyIndex::~RingKeyIndex() = default;
RingKeyIndex::RingKeyIndex(RingKeyIndex&&) noexcept = default;
RingKeyIndex& RingKeyIndex::operator=(RingKeyIndex&&) noexcept = default;

bool RingKeyIndex::add(const Eigen::VectorXf& key, std::uint32_t item) {
    if (key.size() != dim_ || !key.allFinite()) return false;
    keys_.insert(keys_.end(), key.data(), key.data() + dim_);
    items_.push_back(item);
    if (items_.size() - indexed_ >= rebuild_every_) rebuild();
    return true;
}

void RingKeyIndex::rebuild() {
    // The tree holds a pointer to keys_: rebuilt whenever keys_ may have reallocated.
    tree_.reset();
    indexed_ = items_.size();
    if (indexed_ == 0) return;
    tree_ = std::make_unique<Tree>(&keys_, indexed_, dim_);
}

std::vector<RingKeyNeighbour> RingKeyIndex::nearest(const Eigen::VectorXf& key,
                                                    std::size_t k) const {
    std::vector<RingKeyNeighbour> out;
    if (key.size() != dim_ || k == 0 || items_.empty()) return out;
    // The tree reads keys_ through a pointer to the vector, which moves with this object: point
    // it here. Rows [0, indexed_) never change, so the tree itself stays valid as keys_ grows.
    std::vector<std::pair<float, std::uint32_t>> found;  // (squared distance, row)
    if (tree_) {
        tree_->adaptor.keys = &keys_;
        const std::size_t kk = std::min(k, indexed_);
        std::vector<std::uint32_t> rows(kk);
        std::vector<float> d2(kk);
        const std::size_t n = tree_->index.knnSearch(key.data(), kk, rows.data(), d2.data());
        for (std::size_t i = 0; i < n; ++i) found.emplace_back(d2[i], rows[i]);
    }
    for (std::size_t row = indexed_; row < items_.size(); ++row) {
        const float* p = &keys_[row * std::size_t(dim_)];
        float d2 = 0.0f;
        for (int d = 0; d < dim_; ++d) d2 += (p[d] - key[d]) * (p[d] - key[d]);
        found.emplace_back(d2, std::uint32_t(row));
    }
    const std::size_t n = std::min(k, found.size());
    std::partial_sort(found.begin(), found.begin() + n, found.end());
    out.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
        out.push_back({items_[found[i].second], std::sqrt(found[i].first)});
    }
    return out;
}

void RingKeyIndex::clear() {
    keys_.clear();
    items_.clear();
    indexed_ = 0;
    tree_.reset();
}

}  // namespace ltm::places
