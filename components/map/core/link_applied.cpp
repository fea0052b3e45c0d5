#include "map/core/link_applied.hpp"

#include <algorithm>
#include <cinttypes>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "common/core/file_io.hpp"
#include "common/core/io_error.hpp"
#include "map/core/map_manifest.hpp"

namespace ltm::map {

std::string write_link_applied(const LinkApplied& applied, std::uint64_t manifest_hash) {
    char line[64];
    std::snprintf(line, sizeof line, "manifest %016" PRIx64 "\n", manifest_hash);
    std::string out = line;
    for (const auto& [robot, runs] : applied)
        for (const auto& [run, through] : runs) {
            std::snprintf(line, sizeof line, " %016" PRIx64 " %" PRIu64 "\n", run, through);
            out += "link " + robot + line;
        }
    return out;
}

namespace {
bool hex16(const std::string& s) {
    return s.size() == 16 && std::all_of(s.begin(), s.end(), [](char c) {
               return std::isxdigit(static_cast<unsigned char>(c));
           });
}
}  // namespace

LinkApplied parse_link_applied(const std::string& text, std::uint64_t* manifest_hash) {
    LinkApplied applied;
    bool have_manifest = false;
    std::istringstream in(text);
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
        std::istringstream words(line);
        std::string key, robot, run, through, extra;
        if (!(words >> key)) continue;  // a blank line
        const auto fail = [&](const std::string& problem) {
            throw common::FormatError(kLinkAppliedFile,
                                      "line " + std::to_string(number) + ": " + problem);
        };
        if (!have_manifest) {
            std::string hash;
            if (key != "manifest" || !(words >> hash) || (words >> extra) || !hex16(hash))
                fail("expected 'manifest <16 hex digits>' first");
            if (manifest_hash) *manifest_hash = std::stoull(hash, nullptr, 16);
            have_manifest = true;
            continue;
        }
        if (key != "link") fail("unknown entry '" + key + "' (expected 'link')");
        if (!(words >> robot >> run >> through) || (words >> extra))
            fail("expected 'link <robot> <run> <through>'");
        const bool hex = hex16(run);
        const bool digits = !through.empty() && through.size() <= 20 &&
                            std::all_of(through.begin(), through.end(), [](char c) {
                                return std::isdigit(static_cast<unsigned char>(c));
                            });
        if (!hex) fail("run '" + run + "' is not 16 hex digits");
        if (!digits) fail("through '" + through + "' is not a count");
        std::uint64_t& t = applied[robot][std::stoull(run, nullptr, 16)];
        t = std::max<std::uint64_t>(t, std::stoull(through));
    }
    if (!have_manifest)
        throw common::FormatError(kLinkAppliedFile, "empty: no 'manifest' line (cut short?)");
    return applied;
}

namespace {
std::uint64_t manifest_hash_of(const std::string& map_dir) {
    return map_file_hash(common::read_file(map_dir + "/" + kManifestFile, kManifestFile));
}
}  // namespace

LinkApplied read_link_applied(const std::string& map_dir, std::string* note) {
    const std::string path = map_dir + "/" + kLinkAppliedFile;
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) return {};
    std::uint64_t hash = 0;
    LinkApplied applied = parse_link_applied(common::read_file(path, kLinkAppliedFile), &hash);
    if (hash != manifest_hash_of(map_dir)) {
        if (note)
            *note = map_dir + "/" + kLinkAppliedFile +
                    " was written with another save's manifest: not used (nothing of the link "
                    "counted as held)";
        return {};
    }
    return applied;
}

void save_link_applied(const std::string& map_dir, const LinkApplied& applied) {
    common::write_file_atomic(map_dir + "/" + kLinkAppliedFile,
                              write_link_applied(applied, manifest_hash_of(map_dir)));
}

void merge_link_applied(LinkApplied& into, const LinkApplied& from) {
    for (const auto& [robot, runs] : from)
        for (const auto& [run, through] : runs) {
            std::uint64_t& t = into[robot][run];
            t = std::max(t, through);
        }
}

void DeliveryTracker::mark(const std::string& slot, const std::string& robot, std::uint64_t run,
                           std::uint64_t through, const LinkCounts& delivered) {
    pending_[slot].push_back({robot, run, through, delivered});
    settle(slot);
}

void DeliveryTracker::took_keyframe(const std::string& slot) {
    ++taken_[slot].keyframes;
    settle(slot);
}
void DeliveryTracker::took_local_map(const std::string& slot) {
    ++taken_[slot].local_maps;
    settle(slot);
}
void DeliveryTracker::took_map_changes(const std::string& slot) {
    ++taken_[slot].map_changes;
    settle(slot);
}

std::size_t DeliveryTracker::pending() const {
    std::size_t n = 0;
    for (const auto& [slot, marks] : pending_) n += marks.size();
    return n;
}

bool DeliveryTracker::reached(const LinkCounts& need, const LinkCounts& have) const {
    return have.keyframes >= need.keyframes && have.local_maps >= need.local_maps &&
           (!reads_map_changes_ || have.map_changes >= need.map_changes);
}

// Marks come in the order the downlink handed the messages on and counts only grow, so the
// marks reached are a prefix of the pending ones.
void DeliveryTracker::settle(const std::string& slot) {
    auto it = pending_.find(slot);
    if (it == pending_.end()) return;
    const LinkCounts& have = taken_[slot];
    while (!it->second.empty() && reached(it->second.front().counts, have)) {
        const Mark& m = it->second.front();
        std::uint64_t& t = applied_[m.robot][m.run];
        t = std::max(t, m.through);
        it->second.pop_front();
    }
}

}  // namespace ltm::map
