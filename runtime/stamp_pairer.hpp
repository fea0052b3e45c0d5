#pragma once
// Pairs scans with the poses of the same stamp when both come on separate topics (a scan and the
// odometry's pose of it, a scan and the mapping's corrected pose). A scan waits, in order, until
// its pose comes (it is handed on with it), or until the pose will not come (it is handed on
// without): a newer pose came, the producer said it has none for that stamp (add_no_pose), or it
// waited `wait_s` of wall time. Poses older than a paired one are of no use any more.
// No threads, no DDS: the component calls it from its own thread.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <deque>
#include <limits>
#include <optional>
#include <utility>

namespace ltm::runtime {

struct StampPairerOptions {
    double same_stamp = 1e-4;       // a scan and its pose [s]
    std::size_t max_poses = 200;    // poses kept for pairing (the oldest go first)
    std::size_t max_waiting = 0;    // scans waiting (0: no bound); a full queue drops its oldest
    std::size_t max_no_pose = 200;  // stamps the producer said it has no pose for
    // Wall time a scan waits at most [s] (0: none, infinity: until its pose or a newer one).
    double wait_s = std::numeric_limits<double>::infinity();
};

template <class Scan, class Pose>
class StampPairer {
  public:
    using Clock = std::chrono::steady_clock;

    explicit StampPairer(StampPairerOptions options = {}) : options_(options) {}

    // A scan to pair; a full queue drops its oldest scan first (counted by dropped()).
    void add_scan(double stamp, Scan scan, Clock::time_point now = Clock::now()) {
        if (options_.max_waiting > 0 && waiting_.size() >= options_.max_waiting) {
            waiting_.pop_front();
            ++dropped_;
        }
        waiting_.push_back({stamp, now, std::move(scan)});
    }

    void add_pose(double stamp, Pose pose) {
        newest_pose_ = std::max(newest_pose_, stamp);
        if (poses_.size() >= options_.max_poses) poses_.pop_front();
        poses_.emplace_back(stamp, std::move(pose));
    }

    // The producer has no pose for the scan of this stamp (it lost or skipped it).
    void add_no_pose(double stamp) {
        if (no_pose_.size() >= options_.max_no_pose) no_pose_.pop_front();
        no_pose_.push_back(stamp);
    }

    // Hands on, oldest first, every waiting scan whose pose came or will not come:
    // fn(double stamp, Scan&& scan, std::optional<Pose>&& pose).
    template <class Fn>
    void release(Fn&& fn, Clock::time_point now = Clock::now()) {
        while (!waiting_.empty()) {
            Waiting& w = waiting_.front();
            std::optional<Pose> pose = take_pose(w.stamp);
            if (!pose && !(newest_pose_ > w.stamp + options_.same_stamp) && !no_pose_for(w.stamp) &&
                !waited_enough(w, now))
                break;
            Waiting out = std::move(w);
            waiting_.pop_front();
            fn(out.stamp, std::move(out.scan), std::move(pose));
        }
    }

    // The scans still waiting, oldest first (their poses will not come: at shutdown).
    template <class Fn>
    void release_all(Fn&& fn) {
        while (!waiting_.empty()) {
            Waiting out = std::move(waiting_.front());
            waiting_.pop_front();
            fn(out.stamp, std::move(out.scan), std::optional<Pose>());
        }
    }

    // The wall time a scan waits at most from now on (StampPairerOptions::wait_s).
    void set_wait_s(double wait_s) { options_.wait_s = wait_s; }
    std::size_t waiting() const { return waiting_.size(); }
    // The waiting scans' bytes, each as `bytes(scan)` says.
    template <class Fn>
    std::size_t waiting_bytes(Fn bytes) const {
        std::size_t n = 0;
        for (const Waiting& w : waiting_) n += sizeof(Waiting) + bytes(w.scan);
        return n;
    }
    std::uint64_t dropped() const { return dropped_; }

  private:
    struct Waiting {
        double stamp;
        Clock::time_point arrived;
        Scan scan;
    };

    std::optional<Pose> take_pose(double stamp) {
        for (auto it = poses_.begin(); it != poses_.end(); ++it) {
            if (std::abs(it->first - stamp) >= options_.same_stamp) continue;
            std::optional<Pose> pose(std::move(it->second));
            poses_.erase(poses_.begin(), it + 1);  // older poses are of no use any more
            return pose;
        }
        return std::nullopt;
    }

    bool waited_enough(const Waiting& w, Clock::time_point now) const {
        return std::isfinite(options_.wait_s) &&
               now - w.arrived >= std::chrono::duration<double>(options_.wait_s);
    }

    bool no_pose_for(double stamp) const {
        for (double t : no_pose_)
            if (std::abs(t - stamp) < options_.same_stamp) return true;
        return false;
    }

    StampPairerOptions options_;
    std::deque<Waiting> waiting_;
    std::deque<std::pair<double, Pose>> poses_;
    std::deque<double> no_pose_;
    double newest_pose_ = -1e300;
    std::uint64_t dropped_ = 0;
};

}  // namespace ltm::runtime
