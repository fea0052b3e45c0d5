#include "map/core/site_staging.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>

#include "common/core/file_io.hpp"
#include "common/core/io_error.hpp"
#include "map/core/site_lock.hpp"
#include "map/core/site_store.hpp"

namespace ltm::map {
namespace {

namespace fs = std::filesystem;

constexpr const char* kMarkerHeader = "ltm site staging";

// The first line of a small file ("" when unreadable).
std::string first_line(const std::string& path) {
    std::ifstream in(path);
    std::string line;
    std::getline(in, line);
    return line;
}

// This process, as no other process on any boot is: the boot's id, the pid and the process's
// start time (clock ticks since boot, /proc/self/stat field 22).
std::string process_identity() {
    std::string start = "0";
    std::ifstream stat("/proc/self/stat");
    std::string all((std::istreambuf_iterator<char>(stat)), std::istreambuf_iterator<char>());
    const auto close = all.rfind(')');  // the command name may hold spaces
    if (close != std::string::npos) {
        std::istringstream fields(all.substr(close + 2));
        std::string f;
        for (int i = 3; i <= 22 && (fields >> f); ++i)
            if (i == 22) start = f;
    }
    std::string boot = first_line("/proc/sys/kernel/random/boot_id");
    if (boot.empty()) boot = "noboot";
    return boot + "/" + std::to_string(::getpid()) + "/" + start;
}

std::string utc_now() {
    const std::time_t t = std::time(nullptr);
    std::tm tm{};
    gmtime_r(&t, &tm);
    char buf[32];
    std::strftime(buf, sizeof buf, "%Y-%m-%d %H:%M:%S UTC", &tm);
    return buf;
}

// The claims of this process, by site (canonical path): a composed host's components share one.
std::mutex g_mutex;
std::mutex g_claiming;  // one claim made at a time (two would find each other's lock taken)
std::map<std::string, std::weak_ptr<StagingClaim>> g_claims;
unsigned long g_claims_made = 0;  // guarded by g_mutex: each new claim is a new session

std::string site_key(const std::string& site_dir) {
    std::error_code ec;
    const fs::path p = fs::weakly_canonical(fs::absolute(site_dir), ec);
    return ec ? site_dir : p.string();
}

}  // namespace

std::string StagingMark::describe() const {
    if (id.empty()) return "unmarked";
    return "pid " + std::to_string(pid) + ", claimed " + claimed;
}

StagingMark read_staging_mark(const std::string& site_dir) {
    StagingMark m;
    std::ifstream in(SiteStore(site_dir).staging_marker_file());
    std::string line;
    if (!std::getline(in, line) || line != kMarkerHeader) return m;
    StagingMark read;
    while (std::getline(in, line)) {
        const auto space = line.find(' ');
        if (space == std::string::npos) continue;
        const std::string key = line.substr(0, space), value = line.substr(space + 1);
        if (key == "session") read.id = value;
        if (key == "pid") read.pid = std::strtol(value.c_str(), nullptr, 10);
        if (key == "claimed") read.claimed = value;
    }
    return read.id.empty() ? m : read;
}

StagingClaim::StagingClaim(const std::string& site_dir) : site_dir_(site_dir) {
    const SiteStore store(site_dir);
    lock_ = std::make_unique<SiteLock>(store.lock_file());  // throws: another live session
    {
        std::lock_guard<std::mutex> lock(g_mutex);
        mark_.id = process_identity() + "/" + std::to_string(++g_claims_made);
    }
    mark_.pid = long(::getpid());
    mark_.claimed = utc_now();

    // Whatever staging is there now belongs to an earlier session: this one has written nothing
    // yet (its writers claim before they write), and a session of another live process would
    // hold the lock.
    const fs::path staging(store.staging_dir());
    std::error_code ec;
    if (fs::exists(staging, ec)) {
        const StagingMark earlier = read_staging_mark(site_dir);
        fs::remove_all(staging, ec);
        if (ec)
            throw common::IoError(staging.string(),
                                  "cannot remove an earlier session's staging: " + ec.message());
        removed_ = "removed " + staging.string() +
                   ": the staging of a session that did not finish (" + earlier.describe() + ")";
    }
    fs::create_directories(staging, ec);
    if (ec) throw common::IoError(staging.string(), "cannot create the staging: " + ec.message());
    common::write_file_atomic(SiteStore(site_dir).staging_marker_file(),
                              std::string(kMarkerHeader) + "\nsession " + mark_.id + "\npid " +
                                  std::to_string(mark_.pid) + "\nclaimed " + mark_.claimed + "\n");
    common::sync_folder(staging.parent_path().string());
}

StagingClaim::~StagingClaim() = default;

std::string StagingClaim::staging_problem() const {
    const std::string staging = SiteStore(site_dir_).staging_dir();
    std::error_code ec;
    if (!fs::is_directory(staging, ec)) return "no staging: " + staging + " is gone";
    const StagingMark now = read_staging_mark(site_dir_);
    if (now.id == mark_.id) return "";
    return "the staging " + staging + " is not this session's (its marker: " + now.describe() +
           "; this session: " + mark_.describe() + ")";
}

std::shared_ptr<StagingClaim> claim_staging(const std::string& site_dir, bool* made) {
    const std::string key = site_key(site_dir);
    std::lock_guard<std::mutex> claiming(g_claiming);
    {
        std::lock_guard<std::mutex> lock(g_mutex);
        if (std::shared_ptr<StagingClaim> held = g_claims[key].lock()) {
            if (made) *made = false;
            return held;
        }
    }
    auto claim = std::make_shared<StagingClaim>(site_dir);
    {
        std::lock_guard<std::mutex> lock(g_mutex);
        g_claims[key] = claim;
    }
    if (made) *made = true;
    return claim;
}

}  // namespace ltm::map
