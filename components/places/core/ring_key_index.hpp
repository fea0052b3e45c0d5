#pragma once
// Nearest ring keys (Scan Context retrieval): a k-d tree (nanoflann) over the keys added so far,
// rebuilt once enough keys have arrived since the last build; the keys not yet in the tree are
// searched by brute force, so every added key is always found.
#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <vector>

namespace ltm::places {

struct RingKeyNeighbour {
    std::uint32_t item = 0;  // the value given to add()
    float distance = 0.0f;   // Euclidean distance between the keys
};

class RingKeyIndex {
  public:
    // dim: key length (the descriptor's rings); rebuild_every: keys added before the tree is
    // rebuilt (they are brute-forced until then).
    explicit RingKeyIndex(int dim, std::size_t rebuild_every = 64);
    ~RingKeyIndex();
    RingKeyIndex(RingKeyIndex&&) noexcept;
    RingKeyIndex& operator=(RingKeyIndex&&) noexcept;

    int dim() const { return dim_; }
    std::size_t size() const { return items_.size(); }
    // key.size() must equal dim(); returns false (nothing added) otherwise or when not finite.
    bool add(const Eigen::VectorXf& key, std::uint32_t item);
    // The k nearest keys, nearest first (fewer when the index holds fewer).
    std::vector<RingKeyNeighbour> nearest(const Eigen::VectorXf& key, std::size_t k) const;
    void clear();

  private:
    struct Tree;
    void rebuild();

    int dim_;
    std::size_t rebuild_every_;
    std::vector<float> keys_;  // size() x dim, row-major
    std::vector<std::uint32_t> items_;
    std::size_t indexed_ = 0;  // keys [0, indexed_) are in the tree
    std::unique_ptr<Tree> tree_;
};

}  // namespace ltm::places
