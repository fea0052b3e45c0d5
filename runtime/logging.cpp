#include "runtime/logging.hpp"

#include <atomic>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <memory>
#include <mutex>

#include "runtime/log_file.hpp"

namespace ltm::runtime {
namespace {
std::atomic<int> g_level{static_cast<int>(LogLevel::kInfo)};
std::mutex g_file_mutex;
std::shared_ptr<RotatingLogFile> g_file;  // the launch config's `log: file:`, when given
}  // namespace

void set_log_level(LogLevel level) { g_level = static_cast<int>(level); }
LogLevel log_level() { return static_cast<LogLevel>(g_level.load()); }

void set_log_file(std::shared_ptr<RotatingLogFile> file) {
    std::lock_guard<std::mutex> lock(g_file_mutex);
    g_file = std::move(file);
}

void log(LogLevel level, const std::string& who, const std::string& message) {
    if (static_cast<int>(level) < g_level.load()) return;
    static const char* names[] = {"debug", "info", "warn", "error"};
    const auto now = std::chrono::system_clock::now();
    const std::time_t t = std::chrono::system_clock::to_time_t(now);
    const int ms = static_cast<int>(
        std::chrono::duration_cast<std::chrono::milliseconds>(now.time_since_epoch()).count() %
        1000);
    std::tm tm{};
    localtime_r(&t, &tm);
    char stamp[32];
    std::strftime(stamp, sizeof stamp, "%H:%M:%S", &tm);
    // One fprintf per line: lines from different threads do not interleave.
    std::fprintf(stderr, "%s.%03d %-5s [%s] %s\n", stamp, ms, names[static_cast<int>(level)],
                 who.c_str(), message.c_str());
    std::shared_ptr<RotatingLogFile> file;
    {
        std::lock_guard<std::mutex> lock(g_file_mutex);
        file = g_file;
    }
    if (!file) return;
    char head[64];
    std::snprintf(head, sizeof head, "%s.%03d %-5s [", stamp, ms, names[static_cast<int>(level)]);
    const std::string note = file->write(head + who + "] " + message + "\n");
    if (!note.empty())
        std::fprintf(stderr, "%s.%03d %-5s [host] %s\n", stamp, ms, "warn", note.c_str());
}

}  // namespace ltm::runtime
