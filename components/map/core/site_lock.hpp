#pragma once
// SITE/lock: one session on a site at a time. The host that runs a session holds an exclusive
// flock(2) on the file for as long as the lock object lives and writes its pid into it; the
// kernel drops the lock when the process dies (kill -9, power loss), so a lock is never stale.
#include <string>

namespace ltm::map {

class SiteLock {
  public:
    // Takes the lock (creating the site folder and the file when missing). Throws common::IoError
    // with one line when another process holds it ("SITE/lock: the site is in use by pid 4242 (a
    // session runs on it); stop it first") or the file cannot be made.
    explicit SiteLock(const std::string& path);
    ~SiteLock();
    SiteLock(const SiteLock&) = delete;
    SiteLock& operator=(const SiteLock&) = delete;
    // Lets go (also done by the destructor); the file stays, empty.
    void release();

  private:
    std::string path_;
    int fd_ = -1;
};

}  // namespace ltm::map
