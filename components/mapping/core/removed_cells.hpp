#pragma once
// Cells of the map frame that map maintenance found emptied (the voxels of objects that vanished
// or moved, components/maintenance): the Mapper clears the local maps' voxels there, now and in
// local maps that arrive later (a snapshot of a map still being built holds them again). A hash set
// of cells of one edge length (the first one given); bounded: beyond `capacity` cells new ones are
// not recorded (the maps present are still cleared) and full() says so. The cells of vanished
// objects are also kept apart (add_surface): they take the voxels whose own surface they lie on a
// little farther (MapEditConfig, mapper_config.hpp).
//
// Most voxels looked at (every voxel of a local map near a pass's cells, every snapshot the
// odometry sends) are nowhere near a removed cell: a coarse count of the cells in blocks of
// kBlock^3 answers those with one look-up before the cells' own 8 to ~130 (issue 28).
#include <Eigen/Core>
#include <cstdint>
#include <unordered_map>
#include <unordered_set>
#include <vector>

namespace ltm::mapping {

class RemovedCells {
  public:
    explicit RemovedCells(std::size_t capacity = 2'000'000) : capacity_(capacity) {}

    // Records the cells of edge `cell_size` (> 0) holding `centres`; the first call fixes the
    // lattice, later centres are put on it. Non-finite centres are skipped. Cells recorded.
    std::size_t add(const std::vector<Eigen::Vector3f>& centres, float cell_size);
    // The same for the cells of a vanished object (add() them too): see surface_near().
    std::size_t add_surface(const std::vector<Eigen::Vector3f>& centres, float cell_size);
    // Forgets the cells holding `centres` (new objects stand there now), in both sets.
    void erase(const std::vector<Eigen::Vector3f>& centres);
    // True when p lies in a recorded cell or within half a cell of one (the 2x2x2 cells nearest
    // to p): a voxel's centre is the mean of its points, which can sit up to half a cell off.
    bool covers(const Eigen::Vector3f& p) const;
    // True when a recorded cell's centre lies within `radius` of p, or covers(p): a voxel larger
    // than a cell is taken with a cell within its reach (radius: half the voxel's edge).
    bool covers(const Eigen::Vector3f& p, float radius) const;
    // True when the centre of a vanished object's cell (add_surface) lies within `reach` of p and
    // within `band` of the plane through p with unit normal n: on the surface of a voxel centred
    // at p.
    bool surface_near(const Eigen::Vector3f& p, const Eigen::Vector3f& n, float reach,
                      float band) const;

    bool empty() const { return all_.cells.empty(); }
    bool surfaces_empty() const { return surface_.cells.empty(); }
    std::size_t size() const { return all_.cells.size(); }
    std::size_t surface_size() const { return surface_.cells.size(); }
    bool full() const { return full_; }
    float cell_size() const { return size_; }
    // About what the sets hold (their buckets and nodes, with malloc's 16 B a node).
    std::size_t memory_bytes() const;

  private:
    static constexpr int kBlock = 8;  // cells a block's edge
    struct Set {
        std::unordered_set<std::uint64_t> cells;
        std::unordered_map<std::uint64_t, std::uint32_t> blocks;  // cells recorded in each block
        // Whether any recorded cell lies in the cells lo..hi (inclusive) may be true: false when
        // no block they touch holds a cell.
        bool may_hold(const Eigen::Vector3i& lo, const Eigen::Vector3i& hi) const;
    };
    static std::uint64_t key(const Eigen::Vector3i& c);
    static Eigen::Vector3i block(const Eigen::Vector3i& c);
    // Whether a recorded cell of `set` whose centre lies within `reach` of p passes
    // keep(centre - p) (p finite and in range, reach > 0: the callers check).
    template <class Keep>
    bool any_within(const Set& set, const Eigen::Vector3f& p, float reach, Keep keep) const;
    Eigen::Vector3i cell(const Eigen::Vector3f& p) const;
    std::size_t add_to(Set& set, const std::vector<Eigen::Vector3f>& centres, float cell_size);

    std::size_t capacity_;
    float size_ = 0.0f;
    bool full_ = false;
    Set all_, surface_;
};

}  // namespace ltm::mapping
