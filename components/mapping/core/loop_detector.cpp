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

const LoopDetectorConfig& checked(const ScanContextConfig& sc, const LoopDetectorConfig& c) {
    common::throw_if(validate(sc), "scan_context");
    common::throw_if(validate(c), "loop_detection");
    return c;
}

}  // namespace

LoopDetector::LoopDetector(const ScanContextConfig& sc_config, const LoopDetectorConfig& config)
    : sc_config_(sc_config),
      config_(checked(sc_config, config)),
      index_(sc_config.rings, std::size_t(config.rebuild_every)) {}

bool LoopDetector::fits(const ScanContext& sc) const {
    return sc.kind == sc_config_.kind && sc.rings == sc_config_.rings &&
           sc.sectors == sc_config_.sectors &&
           sc.value.size() == std::size_t(sc.rings) * sc.sectors;
}

void LoopDetector::release(std::uint32_t session, double stamp) {
    // pending_ is in add() order; keyframes of another session are never recent.
    while (!pending_.empty()) {
        const Pending& p = pending_.front();
        const std::size_t newer = descriptors_.size() - 1 - p.item;  // kept after it
        const bool other_session = p.session != session;
        if (!other_session && (newer < std::size_t(config_.exclude_recent_keyframes) ||
                               stamp - p.stamp < config_.exclude_recent_seconds)) {
            break;
        }
        index_.add(ring_key(descriptors_[p.item]), p.item);
        pending_.pop_front();
    }
}

std::vector<LoopCandidate> LoopDetector::query(const ScanContext& descriptor) const {
    std::vector<LoopCandidate> out;
    if (!fits(descriptor) || index_.size() == 0) return out;
    for (const RingKeyNeighbour& n :
         index_.nearest(ring_key(descriptor), std::size_t(config_.candidates))) {
        const ScanContextMatch m = compare(descriptor, descriptors_[n.item], sc_config_);
        if (!m.valid || !(m.distance <= config_.max_distance)) continue;
        out.push_back({n.item, m.distance, m.yaw, m.shift});
    }
    std::sort(out.begin(), out.end(), [](const LoopCandidate& a, const LoopCandidate& b) {
        return a.distance < b.distance || (a.distance == b.distance && a.match < b.match);
    });
    if (out.size() > std::size_t(config_.max_results)) out.resize(std::size_t(config_.max_results));
    return out;
}

bool LoopDetector::add(const ScanContext& descriptor, std::uint32_t session, double stamp,
                       std::vector<LoopCandidate>* candidates) {
    return search(descriptor, session, stamp, candidates) && keep(descriptor, session, stamp);
}

bool LoopDetector::search(const ScanContext& descriptor, std::uint32_t session, double stamp,
                          std::vector<LoopCandidate>* candidates) {
    if (candidates) candidates->clear();
    if (!fits(descriptor)) return false;
    release(session, stamp);  // before the new keyframe joins: it never finds itself
    if (candidates) *candidates = query(descriptor);
    return true;
}

bool LoopDetector::keep(const ScanContext& descriptor, std::uint32_t session, double stamp) {
    if (!fits(descriptor)) return false;
    descriptors_.push_back(descriptor);
    pending_.push_back({std::uint32_t(descriptors_.size() - 1), session, stamp});
    return true;
}

bool LoopDetector::add_searchable(const ScanContext& descriptor) {
    if (!fits(descriptor)) return false;
    descriptors_.push_back(descriptor);
    index_.add(ring_key(descriptor), std::uint32_t(descriptors_.size() - 1));
    return true;
}

}  // namespace ltm::mapping
