#include "mapping/core/loop_detector.hpp"

#include <algorithm>

namespace ltm::mapping {

std::optional<common::ConfigProblem> validate(const LoopDetectorConfig& config) {
    LoopDetectorConfig c =
        config;  // visit_fields takes a mutable config (loaders write through it)
    common::ConfigChecker k;
    visit_fields(c, "", k);
    return k.problem();
}

namespace {

const LoopDetectorConfig& checked(const places::ScanContextConfig& sc,
                                  const LoopDetectorConfig& c) {
    common::throw_if(validate(sc), "scan_context");
    common::throw_if(validate(c), "loop_detection");
    return c;
}

}  // namespace

LoopDetector::LoopDetector(const places::ScanContextConfig& sc_config,
                           const LoopDetectorConfig& config)
    : sc_config_(sc_config),
      config_(checked(sc_config, config)),
      index_(sc_config.rings, std::size_t(config.rebuild_every)) {}

bool LoopDetector::fits(const places::ScanContext& sc) const {
    return sc.kind == sc_config_.kind && sc.rings == sc_config_.rings &&
           sc.sectors == sc_config_.sectors &&
           sc.value.size() == std::size_t(sc.rings) * sc.sectors;
}

void LoopDetector::release(std::uint32_t session, double stamp) {
    const auto it = pending_.find(session);
    if (it == pending_.end()) return;
    std::deque<Pending>& pending = it->second;
    const std::uint64_t kept = kept_[session];
    while (!pending.empty()) {
        const Pending& p = pending.front();
        const std::uint64_t newer = kept - 1 - p.ordinal;  // of its session, kept after it
        if (newer < std::uint64_t(config_.exclude_recent_keyframes) ||
            stamp - p.stamp < config_.exclude_recent_seconds) {
            break;
        }
        index_.add(places::ring_key(descriptors_[p.item]), p.item);
        pending.pop_front();
    }
}

void LoopDetector::query_pending(const places::ScanContext& descriptor, std::uint32_t session,
                                 std::vector<LoopCandidate>* out) const {
    // The nearest ring keys first, as the index does, then the full comparison.
    const Eigen::VectorXf key = places::ring_key(descriptor);
    std::vector<std::pair<float, std::uint32_t>> near;
    for (const auto& [other, pending] : pending_) {
        if (other == session) continue;
        for (const Pending& p : pending)
            near.emplace_back((places::ring_key(descriptors_[p.item]) - key).norm(), p.item);
    }
    const std::size_t n = std::min(near.size(), std::size_t(config_.candidates));
    std::partial_sort(near.begin(), near.begin() + std::ptrdiff_t(n), near.end());
    for (std::size_t i = 0; i < n; ++i) {
        const places::ScanContextMatch m =
            compare(descriptor, descriptors_[near[i].second], sc_config_);
        if (!m.valid || !(m.distance <= config_.max_distance)) continue;
        out->push_back({near[i].second, m.distance, m.yaw, m.shift});
    }
}

std::vector<LoopCandidate> LoopDetector::query(const places::ScanContext& descriptor) const {
    std::vector<LoopCandidate> out;
    if (!fits(descriptor) || index_.size() == 0) return out;
    for (const places::RingKeyNeighbour& n :
         index_.nearest(places::ring_key(descriptor), std::size_t(config_.candidates))) {
        const places::ScanContextMatch m = compare(descriptor, descriptors_[n.item], sc_config_);
        if (!m.valid || !(m.distance <= config_.max_distance)) continue;
        out.push_back({n.item, m.distance, m.yaw, m.shift});
    }
    std::sort(out.begin(), out.end(), [](const LoopCandidate& a, const LoopCandidate& b) {
        return a.distance < b.distance || (a.distance == b.distance && a.match < b.match);
    });
    if (out.size() > std::size_t(config_.max_results)) out.resize(std::size_t(config_.max_results));
    return out;
}

bool LoopDetector::add(const places::ScanContext& descriptor, std::uint32_t session, double stamp,
                       std::vector<LoopCandidate>* candidates) {
    return search(descriptor, session, stamp, candidates) && keep(descriptor, session, stamp);
}

bool LoopDetector::search(const places::ScanContext& descriptor, std::uint32_t session,
                          double stamp, std::vector<LoopCandidate>* candidates) {
    if (candidates) candidates->clear();
    if (!fits(descriptor)) return false;
    release(session, stamp);  // before the new keyframe joins: it never finds itself
    if (!candidates) return true;
    *candidates = query(descriptor);
    // Another session's recent keyframes (robots at once): not recent for this one.
    const std::size_t from_index = candidates->size();
    query_pending(descriptor, session, candidates);
    if (candidates->size() == from_index) return true;
    std::sort(candidates->begin(), candidates->end(),
              [](const LoopCandidate& a, const LoopCandidate& b) {
                  return a.distance < b.distance || (a.distance == b.distance && a.match < b.match);
              });
    if (candidates->size() > std::size_t(config_.max_results))
        candidates->resize(std::size_t(config_.max_results));
    return true;
}

bool LoopDetector::keep(const places::ScanContext& descriptor, std::uint32_t session,
                        double stamp) {
    if (!fits(descriptor)) return false;
    descriptors_.push_back(descriptor);
    pending_[session].push_back({std::uint32_t(descriptors_.size() - 1), kept_[session]++, stamp});
    return true;
}

bool LoopDetector::add_searchable(const places::ScanContext& descriptor) {
    if (!fits(descriptor)) return false;
    descriptors_.push_back(descriptor);
    index_.add(places::ring_key(descriptor), std::uint32_t(descriptors_.size() - 1));
    return true;
}

}  // namespace ltm::mapping
