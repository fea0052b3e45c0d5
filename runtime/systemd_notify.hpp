#pragma once
// systemd's service notification protocol (sd_notify(3)) without libsystemd: one datagram to the
// socket in $NOTIFY_SOCKET. Lets the host run as a `Type=notify` unit with a watchdog
// (launch_configs/systemd/): READY=1 once every component runs, WATCHDOG=1 while they make
// progress, STOPPING=1 on a stop. Outside systemd every call does nothing.
#include <chrono>
#include <string>

namespace ltm::runtime {

class SystemdNotifier {
  public:
    // Reads $NOTIFY_SOCKET, $WATCHDOG_USEC and $WATCHDOG_PID.
    SystemdNotifier();
    bool enabled() const { return !socket_path_.empty(); }
    // The watchdog interval systemd asked for (zero: no watchdog).
    std::chrono::microseconds watchdog_interval() const { return watchdog_; }
    // Sends `state` ("READY=1", "STATUS=...", ...); false when it could not be sent.
    bool notify(const std::string& state) const;

  private:
    std::string socket_path_;  // '@' first: an abstract socket
    std::chrono::microseconds watchdog_{0};
};

}  // namespace ltm::runtime
