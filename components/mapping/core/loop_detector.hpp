#pragma once
// Loop-closure candidates by Scan Context (METHOD.md section 3): every keyframe's descriptor is
// kept; a new keyframe is compared with the keyframes that are not recent (an exclusion window in
// keyframes and seconds within its session), retrieved by ring key from a k-d tree, and the
// column-shift distance under a threshold makes a candidate, with the yaw between the scans.
// Several sessions may run at once (robots on one site): a keyframe of another session is never
// recent, so it is searched from the moment it is kept (the newest ones by ring key among those
// still recent for their own session), while its own session sees it only after the window.
// The caller verifies candidates geometrically.
#include <cstdint>
#include <deque>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "places/core/ring_key_index.hpp"
#include "places/core/scan_context.hpp"

namespace ltm::mapping {

struct LoopDetectorConfig {
    int candidates = 10;                   // nearest ring keys compared in full
    double max_distance = 0.35;            // descriptor distance threshold (kMaxHeight: 0..1)
    int exclude_recent_keyframes = 50;     // the last N keyframes of the session are not searched
    double exclude_recent_seconds = 30.0;  // nor the keyframes less than this older [s]
    int max_results = 3;                   // best candidates returned
    int rebuild_every = 64;                // keys added between k-d tree rebuilds
};

// Calls v(key, field, rule) for every field, keys under `prefix` ("loop_detection."); the rule is
// the field's (common/core/config_check.hpp). An infinite limit is no limit.
template <class Visitor>
void visit_fields(LoopDetectorConfig& c, const std::string& prefix, Visitor&& v) {
    using namespace common::rules;
    v(prefix + "candidates", c.candidates, at_least(1));
    v(prefix + "max_distance", c.max_distance, positive.or_infinite());
    v(prefix + "exclude_recent_keyframes", c.exclude_recent_keyframes, non_negative);
    v(prefix + "exclude_recent_seconds", c.exclude_recent_seconds, non_negative.or_infinite());
    v(prefix + "max_results", c.max_results, at_least(1));
    v(prefix + "rebuild_every", c.rebuild_every, at_least(1));
}

// The first field that breaks its rule (key relative: "candidates"); nullopt when valid.
std::optional<common::ConfigProblem> validate(const LoopDetectorConfig& config);

struct LoopCandidate {
    std::uint32_t match = 0;  // index of the earlier keyframe (order of add())
    double distance = 0.0;    // descriptor distance
    double yaw = 0.0;         // R_match_query = Rz(yaw) [rad]
    int shift = 0;            // sectors
    // Found by place, not by descriptor (the Mapper: another robot's keyframe near this one in
    // the graph); distance and yaw are still the descriptors' (for the record).
    bool by_place = false;
};

class LoopDetector {
  public:
    // Throws common::ConfigError (naming the key) on an invalid configuration.
    LoopDetector(const places::ScanContextConfig& sc_config, const LoopDetectorConfig& config);

    const places::ScanContextConfig& scan_context_config() const { return sc_config_; }
    // Descriptors kept, and descriptor i (index = order of add()).
    std::size_t size() const { return descriptors_.size(); }
    const places::ScanContext& descriptor(std::uint32_t i) const { return descriptors_[i]; }
    std::size_t searchable() const { return index_.size(); }

    // The candidates for a new keyframe of `session` taken at `stamp` (best first), then the
    // keyframe's descriptor is kept under index size(). The descriptor must have the configured
    // kind and shape (false: nothing kept, no candidates).
    bool add(const places::ScanContext& descriptor, std::uint32_t session, double stamp,
             std::vector<LoopCandidate>* candidates);
    // add() in two halves, for a caller that decides after the search whether to keep the
    // keyframe: the candidates (as add() finds them; nothing kept), then keep() it or not.
    bool search(const places::ScanContext& descriptor, std::uint32_t session, double stamp,
                std::vector<LoopCandidate>* candidates);
    bool keep(const places::ScanContext& descriptor, std::uint32_t session, double stamp);
    // A keyframe of an earlier session (a loaded map): searchable at once.
    bool add_searchable(const places::ScanContext& descriptor);
    // Candidates among all searchable keyframes for a descriptor not kept (re-localisation).
    std::vector<LoopCandidate> query(const places::ScanContext& descriptor) const;

  private:
    struct Pending {
        std::uint32_t item;
        std::uint64_t ordinal;  // the keyframes of its session kept before it
        double stamp;
    };
    bool fits(const places::ScanContext& sc) const;
    // Into the index: the keyframes of `session` no longer recent for it.
    void release(std::uint32_t session, double stamp);
    // Candidates among the recent keyframes of the sessions other than `session`.
    void query_pending(const places::ScanContext& descriptor, std::uint32_t session,
                       std::vector<LoopCandidate>* out) const;

    places::ScanContextConfig sc_config_;
    LoopDetectorConfig config_;
    std::vector<places::ScanContext> descriptors_;
    places::RingKeyIndex index_;
    // Per session: recent keyframes, not yet in the index (oldest first), and how many it kept.
    std::map<std::uint32_t, std::deque<Pending>> pending_;
    std::map<std::uint32_t, std::uint64_t> kept_;
};

}  // namespace ltm::mapping
