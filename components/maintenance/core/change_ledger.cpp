#include "maintenance/core/change_ledger.hpp"

#include <cmath>
#include <stdexcept>

#include "common/core/io_error.hpp"
#include "maintenance/core/change_record.hpp"

namespace ltm::maintenance {

ChangeLedger::ChangeLedger(float voxel_size) : voxel_size_(voxel_size) {
    if (!(voxel_size > 0.0f) || !std::isfinite(voxel_size))
        throw std::invalid_argument("change ledger: voxel size must be positive");
}

ChangeLedger::Key ChangeLedger::key(const Eigen::Vector3f& p) const {
    const Eigen::Vector3f q = (p / voxel_size_).array().floor();
    return {static_cast<std::int32_t>(q.x()), static_cast<std::int32_t>(q.y()),
            static_cast<std::int32_t>(q.z())};
}

std::string ChangeLedger::refusal(const ChangeSet& c) const {
    if (std::abs(c.voxel_size - voxel_size_) > 1e-6f * voxel_size_)
        return "voxel size " + std::to_string(c.voxel_size) + " m differs from the map's " +
               std::to_string(voxel_size_) + " m";
    if (records_ > 0 && c.session < session_)
        return "session " + std::to_string(c.session) + " comes before session " +
               std::to_string(session_) + ", already applied";
    for (const SegmentChange& s : c.changes) {
        for (const Eigen::Vector3f& p : s.voxels) {
            // Keys of cells beyond int32 (or non-finite centres) have no place on the lattice.
            const Eigen::Vector3f q = p / voxel_size_;
            if (!q.allFinite() || q.cwiseAbs().maxCoeff() >= 2.0e9f)
                return "segment change " + std::to_string(s.id) + ": a voxel outside the map";
        }
    }
    return "";
}

void ChangeLedger::apply(const ChangeSet& c) {
    const std::string why = refusal(c);
    if (!why.empty()) throw std::invalid_argument(why);
    for (const SegmentChange& s : c.changes) {
        for (const Eigen::Vector3f& p : s.voxels) {
            const Key k = key(p);
            if (s.removed()) {
                added_.erase(k);
                removed_.insert(k);
            } else {
                removed_.erase(k);
                added_.insert(k);
            }
        }
    }
    session_ = c.session;
    ++records_;
}

void ChangeLedger::apply_record(const std::string& path) {
    const ChangeSet c = read_change_record(path);
    const std::string why = refusal(c);
    if (!why.empty()) throw common::FormatError(path, "refused: " + why);
    apply(c);
}

bool ChangeLedger::removed(const Eigen::Vector3f& p) const { return removed_.count(key(p)) > 0; }
bool ChangeLedger::added(const Eigen::Vector3f& p) const { return added_.count(key(p)) > 0; }

bool ChangeLedger::operator==(const ChangeLedger& o) const {
    return voxel_size_ == o.voxel_size_ && removed_ == o.removed_ && added_ == o.added_ &&
           records_ == o.records_ && session_ == o.session_;
}

}  // namespace ltm::maintenance
