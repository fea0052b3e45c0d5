#pragma once
// The localisation's status over a run (ltm_msgs/LocalisationStatus as recorded in MCAP): decoded
// from its CDR, summed up (time in each state, re-localisations, global queries) and drawn.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace ltm::eval {

struct StatusSample {
    double stamp = 0.0;      // [s] the scan's stamp
    std::uint8_t state = 0;  // LocalisationStatus_Constants: 0 initialising .. 4 off the map
    bool pose_valid = false;
    float confidence = 0.0f;
    bool global_ran = false;
    double global_time = 0.0;  // [s] wall time of the global query on this scan
    std::uint32_t relocalisations = 0;
    std::uint32_t skipped_scans = 0;
    std::string message;
};

// A LocalisationStatus message's CDR (encapsulation header included). False, with `error` set to
// one line, when the bytes are not one.
bool decode_localisation_status(const std::uint8_t* data, std::size_t size, StatusSample* out,
                                std::string* error);

constexpr int kStatusStates = 5;
const char* status_state_name(std::uint8_t state);  // "tracking", ...; "unknown" past the end

struct TimelineSummary {
    std::size_t samples = 0;
    double start = 0.0, end = 0.0;             // [s] first and last stamp
    std::size_t in_state[kStatusStates] = {};  // samples in each state
    std::size_t valid = 0;                     // samples with a valid pose
    std::size_t global_queries = 0;
    double global_median = 0.0, global_max = 0.0;  // [s] wall time of a query
    std::uint32_t skipped_scans = 0;               // the last sample's count
    struct Event {
        double stamp = 0.0;
        std::string message;
    };
    std::vector<Event> relocalisations;  // samples in state RELOCALISED
    std::vector<Event> losses;           // first sample of each run of LOST
};
TimelineSummary summarise_timeline(const std::vector<StatusSample>& samples);

// Two panels: the state over time (one band a state) and the confidence; SVG text.
std::string timeline_svg(const std::vector<StatusSample>& samples, const std::string& title);

}  // namespace ltm::eval
