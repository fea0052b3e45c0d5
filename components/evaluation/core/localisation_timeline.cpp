#include "evaluation/core/localisation_timeline.hpp"

#include <algorithm>

#include "common/core/cdr_cursor.hpp"
#include "evaluation/core/svg_plot.hpp"

namespace ltm::eval {

namespace {

const char* const kStateNames[kStatusStates] = {"initialising", "tracking", "lost", "relocalised",
                                                "off the map"};
const char* const kStateColours[kStatusStates] = {"#7f7f7f", "#2ca02c", "#d62728", "#1f77b4",
                                                  "#ff7f0e"};

}  // namespace

const char* status_state_name(std::uint8_t state) {
    return state < kStatusStates ? kStateNames[state] : "unknown";
}

bool decode_localisation_status(const std::uint8_t* data, std::size_t size, StatusSample* out,
                                std::string* error) {
    const std::vector<std::uint8_t> head(data, data + std::min<std::size_t>(size, 4));
    if (!common::is_cdr_le(head)) {
        *error = "not little-endian plain CDR (encapsulation header)";
        return false;
    }
    common::CdrReader r(data, size);
    std::int32_t sec = 0;
    std::uint32_t nanosec = 0;
    std::string frame_id;
    std::uint8_t pose_valid = 0, global_ran = 0;
    float inlier_fraction = 0.0f;
    double lost_for = 0.0, since_fix = 0.0;
    StatusSample s;
    if (!(r.read(sec) && r.read(nanosec) && r.read_string(frame_id) && r.read(s.state) &&
          r.read(pose_valid) && r.read(s.confidence) && r.read(inlier_fraction) &&
          r.read(lost_for) && r.read(since_fix) && r.read(global_ran) && r.read(s.global_time) &&
          r.read(s.relocalisations) && r.read(s.skipped_scans) && r.read_string(s.message))) {
        *error = "LocalisationStatus cut short or malformed at byte " + std::to_string(r.pos());
        return false;
    }
    s.stamp = sec + nanosec * 1e-9;
    s.pose_valid = pose_valid != 0;
    s.global_ran = global_ran != 0;
    *out = std::move(s);
    return true;
}

TimelineSummary summarise_timeline(const std::vector<StatusSample>& samples) {
    TimelineSummary t;
    t.samples = samples.size();
    if (samples.empty()) return t;
    t.start = samples.front().stamp;
    t.end = samples.back().stamp;
    std::vector<double> query_times;
    std::uint8_t previous = 255;
    for (const StatusSample& s : samples) {
        t.start = std::min(t.start, s.stamp);
        t.end = std::max(t.end, s.stamp);
        if (s.state < kStatusStates) ++t.in_state[s.state];
        if (s.pose_valid) ++t.valid;
        if (s.global_ran) query_times.push_back(s.global_time);
        if (s.state == 3) t.relocalisations.push_back({s.stamp, s.message});
        if (s.state == 2 && previous != 2) t.losses.push_back({s.stamp, s.message});
        previous = s.state;
    }
    t.skipped_scans = samples.back().skipped_scans;
    t.global_queries = query_times.size();
    if (!query_times.empty()) {
        std::sort(query_times.begin(), query_times.end());
        t.global_median = query_times[query_times.size() / 2];
        t.global_max = query_times.back();
    }
    return t;
}

std::string timeline_svg(const std::vector<StatusSample>& samples, const std::string& title) {
    PlotPanel states;
    states.title = title;
    states.x_label = "time since the first scan [s]";
    states.y_label = "state";
    PlotPanel confidence;
    confidence.title = "Confidence";
    confidence.x_label = states.x_label;
    confidence.y_label = "confidence";
    confidence.y_from_zero = true;
    const double t0 = samples.empty() ? 0.0 : summarise_timeline(samples).start;
    for (int state = 0; state < kStatusStates; ++state) {
        PlotSeries band;
        band.label = kStateNames[state];
        band.color = kStateColours[state];
        band.style = PlotSeries::Style::kMarkers;
        band.width = 2.0;
        for (const StatusSample& s : samples) {
            if (s.state == state) band.points.emplace_back(s.stamp - t0, state);
        }
        if (!band.points.empty()) states.series.push_back(std::move(band));
    }
    PlotSeries c;
    c.label = "confidence";
    c.color = "#1f77b4";
    for (const StatusSample& s : samples) c.points.emplace_back(s.stamp - t0, s.confidence);
    confidence.series.push_back(std::move(c));
    return render_svg({states, confidence}, 900, 260);
}

}  // namespace ltm::eval
