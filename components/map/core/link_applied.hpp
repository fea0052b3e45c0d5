#pragma once
// Which of the robots' link packets a saved map already holds (issue 28, item 4): the base
// station's mapping writes, beside every save, per robot and uplink run the seq every packet up to
// which it had applied (`link_applied.txt` in the map directory, written after the manifest). A
// committed site version so records what its map holds, and the base station's downlink may drop
// those packets from its journal: a restarted base station starts from that version and replays
// only what came after.
//
// The file: `manifest <FNV-1a 64 of the map's manifest.txt, 16 hex digits>`, then one line a run,
// `link <robot> <run, 16 hex digits> <through>`, ascending. The manifest's hash ties the record
// to the save it was written with: a record beside another save's manifest (a version snapshot
// taken while a save replaced the files) is not used.
//
// DeliveryTracker is how the mapping learns it: the downlink says, after handing packets on, "run
// R through seq S took K keyframes, L local maps and C map changes since I started"
// (LinkDelivered); the mapping counts what it took on the same topics, and a mark is applied once
// its counts are reached on every topic the mapping reads (topics it does not read hold nothing for
// its map).
#include <cstdint>
#include <deque>
#include <map>
#include <string>

namespace ltm::map {

inline constexpr const char* kLinkAppliedFile = "link_applied.txt";

// robot -> run -> through.
using LinkApplied = std::map<std::string, std::map<std::uint64_t, std::uint64_t>>;

// The file's text, and back. parse throws common::FormatError naming the line for a malformed one.
std::string write_link_applied(const LinkApplied& applied, std::uint64_t manifest_hash);
LinkApplied parse_link_applied(const std::string& text, std::uint64_t* manifest_hash);
// Reads map_dir/link_applied.txt: empty when there is none (a map made without a link) or when
// it belongs to another manifest than map_dir's (then *note says so). Throws common::IoError
// when it is there and unreadable, common::FormatError when malformed.
LinkApplied read_link_applied(const std::string& map_dir, std::string* note = nullptr);
// Writes it atomically (temporary file, fsync, rename) for the manifest map_dir holds now (call
// right after the save). Throws common::IoError.
void save_link_applied(const std::string& map_dir, const LinkApplied& applied);
// Every entry of `from` into `into`, keeping the larger through.
void merge_link_applied(LinkApplied& into, const LinkApplied& from);

// Messages on the three topics that cross the link.
struct LinkCounts {
    std::uint64_t keyframes = 0, local_maps = 0, map_changes = 0;
};

class DeliveryTracker {
  public:
    // `reads_map_changes`: whether the mapping takes the robot's map_changes (else their count
    // does not hold a mark back).
    explicit DeliveryTracker(bool reads_map_changes = true)
        : reads_map_changes_(reads_map_changes) {}
    // A downlink's mark (after the messages it counts were handed on) on the mapping's input
    // `slot` (its robot's name; "" for one robot on relative topics); `robot`: the name the mark
    // gives (what applied() is keyed by).
    void mark(const std::string& slot, const std::string& robot, std::uint64_t run,
              std::uint64_t through, const LinkCounts& delivered);
    // The mapping took a message on `slot`'s topics (its handler ran to the end).
    void took_keyframe(const std::string& slot);
    void took_local_map(const std::string& slot);
    void took_map_changes(const std::string& slot);
    // What is applied now: the marks reached, and what a loaded map held (seed()).
    const LinkApplied& applied() const { return applied_; }
    void seed(const LinkApplied& loaded) { merge_link_applied(applied_, loaded); }
    std::size_t pending() const;

  private:
    struct Mark {
        std::string robot;
        std::uint64_t run = 0, through = 0;
        LinkCounts counts;
    };
    void settle(const std::string& slot);
    bool reached(const LinkCounts& need, const LinkCounts& have) const;

    bool reads_map_changes_;
    std::map<std::string, LinkCounts> taken_;          // by slot
    std::map<std::string, std::deque<Mark>> pending_;  // by slot, in arrival order
    LinkApplied applied_;
};

}  // namespace ltm::map
