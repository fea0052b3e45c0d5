#pragma once
// The host's log also in a file of bounded size (issue 28, item 4: logs within the budget the
// launch config states): `log: {file: ${LTM_OUT}/host.log, max_mb: 16, keep: 2}`. When the file
// would pass max_mb it becomes FILE.1 (FILE.1 becomes FILE.2, ... the one past `keep` is
// removed) and a new FILE starts: at most (keep + 1) * max_mb on the disk. A disk that refuses
// lines is said once on stderr (the lines still go there) and once when it takes them again.
#include <cstdint>
#include <cstdio>
#include <memory>
#include <mutex>
#include <string>

namespace ltm::runtime {

struct HostLogConfig {
    std::string file;    // "": stderr only (the default; under systemd, journald's own budget)
    double max_mb = 16;  // a file's size at most [MiB]
    int keep = 2;        // rotated files kept beside the current one
};

class RotatingLogFile {
  public:
    // Opens (appends to) the file, creating its folder. Throws common::IoError when it cannot.
    explicit RotatingLogFile(HostLogConfig config);
    ~RotatingLogFile();
    RotatingLogFile(const RotatingLogFile&) = delete;
    RotatingLogFile& operator=(const RotatingLogFile&) = delete;

    // Appends one line (with its '\n'). Returns a note for stderr when the disk starts or stops
    // refusing lines ("" otherwise). Thread-safe.
    std::string write(const std::string& line);
    const HostLogConfig& config() const { return config_; }

  private:
    void rotate();
    bool open();

    HostLogConfig config_;
    std::uint64_t max_bytes_ = 0, size_ = 0, refused_ = 0;
    std::FILE* out_ = nullptr;
    bool failing_ = false;
    std::mutex mutex_;
};

// Every later line of runtime::log also goes to `file` (nullptr: stderr only); defined in
// logging.cpp. Declared here, not in logging.hpp, which nearly every file includes.
void set_log_file(std::shared_ptr<RotatingLogFile> file);

}  // namespace ltm::runtime
