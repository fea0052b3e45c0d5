#pragma once
// One line per message on stderr: time, level, who, what. Safe from any thread.
#include <string>

namespace ltm::runtime {

enum class LogLevel { kDebug = 0, kInfo = 1, kWarn = 2, kError = 3 };

void set_log_level(LogLevel level);
LogLevel log_level();
void log(LogLevel level, const std::string& who, const std::string& message);

class Logger {
  public:
    explicit Logger(std::string who) : who_(std::move(who)) {}
    void debug(const std::string& m) const { log(LogLevel::kDebug, who_, m); }
    void info(const std::string& m) const { log(LogLevel::kInfo, who_, m); }
    void warn(const std::string& m) const { log(LogLevel::kWarn, who_, m); }
    void error(const std::string& m) const { log(LogLevel::kError, who_, m); }
    const std::string& who() const { return who_; }

  private:
    std::string who_;
};

}  // namespace ltm::runtime
