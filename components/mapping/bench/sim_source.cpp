#include "mapping/bench/sim_source.hpp"

#include <algorithm>
#include <cstdio>
#include <stdexcept>

#include "simulator/core/scenario_yaml.hpp"

namespace ltm::mapping::bench {

SimSource::SimSource(const SimSourceOptions& o) : threads_(std::max(o.threads, 0)) {
    sim::ScenarioConfig sc = sim::load_scenario(o.scenario);
    if (o.session < 0 || o.session >= int(sc.sessions.size())) {
        throw sim::ScenarioError(o.scenario + ": no session " + std::to_string(o.session) + " (" +
                                 std::to_string(sc.sessions.size()) + " in the file)");
    }
    sim::RouteConfig& route = sc.sessions[std::size_t(o.session)].route;
    if (o.laps > 0) route.laps = o.laps;
    laps_ = route.laps;
    keep_time_ = sc.sensor.motion_distortion;
    sim_ = std::make_unique<sim::Simulator>(sc, o.session);
}

SimSource::~SimSource() {
    for (auto& f : ahead_) f.wait();
}

std::string SimSource::describe() const {
    double length = 0.0;
    for (std::size_t i = 1; i < size(); ++i)
        length += (sim_->pose(i).translation() - sim_->pose(i - 1).translation()).norm();
    const sim::ScenarioConfig& sc = sim_->scenario();
    char buf[256];
    std::snprintf(buf, sizeof buf,
                  "%s session %d (%s), sensor %s, %d lap(s), %.1f m of true path, %zu objects",
                  sc.name.c_str(), sim_->session(),
                  sc.sessions[std::size_t(sim_->session())].name.c_str(), sc.sensor.model.c_str(),
                  laps_, length, sim_->objects().size());
    return buf;
}

common::PoseList SimSource::reference() const {
    common::PoseList out(size());
    for (std::size_t i = 0; i < size(); ++i) out[i] = sim_->pose(i);
    return out;
}

common::PointCloud SimSource::load(std::size_t i) {
    if (i >= size()) throw std::out_of_range("SimSource::load: no scan " + std::to_string(i));
    if (i != next_) {  // out of order: drop what was rendered ahead
        for (auto& f : ahead_) f.wait();
        ahead_.clear();
        next_ = i;
    }
    const sim::Simulator* sim = sim_.get();
    auto render = [sim](std::size_t k) {
        sim::SimScan s;
        sim->scan(k, s);
        return s;
    };
    // The scan asked for, then up to threads_ more, each on its own worker.
    while (ahead_.size() < std::size_t(threads_) + 1 && next_ + ahead_.size() < size()) {
        const std::size_t k = next_ + ahead_.size();
        ahead_.push_back(ahead_.empty() ? std::async(std::launch::deferred, render, k)
                                        : std::async(std::launch::async, render, k));
    }
    sim::SimScan scan = ahead_.front().get();
    ahead_.pop_front();
    ++next_;
    if (!keep_time_) scan.cloud.time.clear();
    return std::move(scan.cloud);
}

}  // namespace ltm::mapping::bench
