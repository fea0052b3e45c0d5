#include "localisation/core/neighbourhood_builder.hpp"

#include <algorithm>
#include <cmath>

#include "common/core/config_check.hpp"

namespace ltm::localisation {

void validate(const NeighbourhoodConfig& c) {
    if (!(c.radius >= 0.0) || !std::isfinite(c.radius)) {
        throw common::ConfigError("neighbourhood.radius", "must be >= 0 (0: no paging)");
    }
    if (!(c.page_above_mb >= 0.0) || !std::isfinite(c.page_above_mb)) {
        throw common::ConfigError("neighbourhood.page_above_mb", "must be >= 0 (0: always paged)");
    }
    if (c.radius > 0.0 && !(c.rebuild_distance > 0.0 && c.rebuild_distance < c.radius)) {
        throw common::ConfigError("neighbourhood.rebuild_distance",
                                  "must be > 0 and below neighbourhood.radius");
    }
}

NeighbourhoodBuilder::NeighbourhoodBuilder(std::shared_ptr<const MapPages> pages,
                                           const NeighbourhoodConfig& config,
                                           const Eigen::Vector3d& start)
    : pages_(std::move(pages)), config_(config), asked_(start) {
    validate(config_);
    std::vector<std::string> refused;
    const double radius = config_.radius > 0.0 ? config_.radius : HUGE_VAL;
    current_ = pages_->build(start, radius, &refused);
    builds_ = 1;
    refused_ = std::move(refused);
    thread_ = std::thread([this] { run(); });
}

NeighbourhoodBuilder::~NeighbourhoodBuilder() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stop_ = true;
    }
    wake_.notify_all();
    thread_.join();
}

void NeighbourhoodBuilder::run() {
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
        wake_.wait(lock, [this] { return stop_ || request_.has_value(); });
        if (stop_) return;
        const Eigen::Vector3d centre = *request_;
        request_.reset();
        busy_ = true;
        lock.unlock();
        std::vector<std::string> refused;
        auto built = pages_->build(centre, config_.radius, &refused);
        lock.lock();
        busy_ = false;
        ready_ = std::move(built);
        ++builds_;
        refused_.insert(refused_.end(), refused.begin(), refused.end());
        if (!request_) idle_.notify_all();
    }
}

void NeighbourhoodBuilder::take_ready() {
    if (!ready_) return;
    const double now = (current_->centre - asked_).head<2>().norm();
    if (ready_->complete || (ready_->centre - asked_).head<2>().norm() <= now)
        current_ = std::move(ready_);
    ready_.reset();
}

bool NeighbourhoodBuilder::update(const Eigen::Vector3d& pose) {
    std::lock_guard<std::mutex> lock(mutex_);
    const std::shared_ptr<const Neighbourhood> before = current_;
    take_ready();
    const bool swapped = current_ != before;
    if (current_->complete || config_.radius <= 0.0) return swapped;  // the whole map is held
    if ((pose - asked_).head<2>().norm() >= config_.rebuild_distance) {
        asked_ = pose;
        request_ = pose;
        wake_.notify_all();
    }
    return swapped;
}

bool NeighbourhoodBuilder::holds(const Eigen::Vector3d& p) const { return holds_locked(p); }

bool NeighbourhoodBuilder::holds_locked(const Eigen::Vector3d& p) const {
    return current_->complete ||
           (p - current_->centre).head<2>().norm() <= config_.radius - config_.rebuild_distance;
}

bool NeighbourhoodBuilder::adopt(const std::shared_ptr<const Neighbourhood>& n,
                                 const Eigen::Vector3d& pose) {
    if (!n || !n->target) return false;
    std::lock_guard<std::mutex> lock(mutex_);
    if (holds_locked(pose)) return false;
    const std::vector<std::uint64_t> want = pages_->nodes_near(pose, config_.radius);
    if (!std::includes(n->nodes.begin(), n->nodes.end(), want.begin(), want.end())) return false;
    // The same local maps (or more), centred where tracking goes on.
    auto here = std::make_shared<Neighbourhood>(*n);
    here->centre = pose;
    here->radius = config_.radius;
    current_ = std::move(here);
    asked_ = pose;
    request_.reset();
    return true;
}

void NeighbourhoodBuilder::settle() {
    std::unique_lock<std::mutex> lock(mutex_);
    idle_.wait(lock, [this] { return !busy_ && !request_; });
    take_ready();
}

std::size_t NeighbourhoodBuilder::builds() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return builds_;
}

std::vector<std::string> NeighbourhoodBuilder::refused() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return refused_;
}

}  // namespace ltm::localisation
