#pragma once
// Clocks, run ids and run folders of the link components.
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace ltm::link {

inline double mono_s() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

inline std::int64_t wall_ns() {
    return std::chrono::duration_cast<std::chrono::nanoseconds>(
               std::chrono::system_clock::now().time_since_epoch())
        .count();
}

// A random, non-zero run id.
inline std::uint64_t new_run_id() {
    std::random_device rd;
    std::uint64_t v = 0;
    while (v == 0) v = (static_cast<std::uint64_t>(rd()) << 32) ^ rd();
    return v;
}

inline std::string run_hex(std::uint64_t run) {
    std::ostringstream s;
    s << std::hex << run;
    return s.str();
}

// The journal folders in `dir` (named by their run's id in hex, run_hex), with their runs; none
// when `dir` does not exist. Other entries are skipped.
inline std::vector<std::pair<std::uint64_t, std::string>> run_folders(const std::string& dir) {
    namespace fs = std::filesystem;
    std::vector<std::pair<std::uint64_t, std::string>> out;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(dir, ec)) {
        const std::string name = e.path().filename().string();
        if (!e.is_directory() || name.empty() || name.size() > 16 ||
            name.find_first_not_of("0123456789abcdef") != std::string::npos)
            continue;
        out.emplace_back(std::stoull(name, nullptr, 16), e.path().string());
    }
    return out;
}

// The robot's name from a namespace: "/robot1" -> "robot1"; "" -> "robot".
inline std::string robot_from_namespace(const std::string& ns) {
    std::string r = ns;
    while (!r.empty() && r.front() == '/') r.erase(r.begin());
    while (!r.empty() && r.back() == '/') r.pop_back();
    return r.empty() ? "robot" : r;
}

}  // namespace ltm::link
