#pragma once
#include <dds/dds.h>

#include <stdexcept>
#include <string>

namespace ltm::runtime {

// A DDS call that failed: what() names the call and dds_strretcode's reason.
class DdsError : public std::runtime_error {
  public:
    DdsError(const std::string& what, dds_return_t rc)
        : std::runtime_error(what + ": " + dds_strretcode(rc)), rc_(rc) {}
    dds_return_t code() const { return rc_; }

  private:
    dds_return_t rc_;
};

// Throws DdsError when `rc` is negative; returns it otherwise.
inline dds_return_t check_dds(dds_return_t rc, const std::string& what) {
    if (rc < 0) throw DdsError(what, rc);
    return rc;
}

}  // namespace ltm::runtime
