#include "link/core/robot_ids.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

#include "common/core/cdr_cursor.hpp"
#include "common/core/io_error.hpp"

namespace ltm::link {
namespace {

const char* const kKeyframe = "ltm_msgs::msg::dds_::Keyframe_";
const char* const kLocalMap = "ltm_msgs::msg::dds_::LocalMap_";
const char* const kMagic = "ltm robot ids 1";

bool skip_header(common::CdrReader& r) {
    std::int32_t sec;
    std::uint32_t nsec;
    return r.read(sec) && r.read(nsec) && r.skip_string();
}

// Where a field was read: its offset, for writing it back.
template <class T>
bool read_at(common::CdrReader& r, T& v, std::size_t& at) {
    if (!r.read(v)) return false;
    at = r.pos() - sizeof(T);
    return true;
}

template <class T>
void write_at(std::vector<std::uint8_t>& cdr, std::size_t at, T v) {
    std::memcpy(cdr.data() + at, &v, sizeof(T));
}

}  // namespace

RobotIdRenumbering::RobotIdRenumbering(std::string file) : file_(std::move(file)) {
    std::ifstream in(file_);
    if (!in) {
        if (errno == ENOENT) return;
        throw common::IoError(file_, std::strerror(errno));
    }
    std::string magic;
    std::getline(in, magic);
    std::string k1, k2, k3;
    std::uint64_t keyframe = 0, local_map = 0, segment = 0;
    if (magic != kMagic || !(in >> k1 >> keyframe >> k2 >> local_map >> k3 >> segment) ||
        k1 != "keyframe" || k2 != "local_map" || k3 != "segment" || segment > UINT32_MAX)
        throw common::IoError(file_, "damaged (expected '" + std::string(kMagic) +
                                         "' and the next keyframe, local_map and segment "
                                         "numbers); the robot's earlier numbers are unknown");
    offsets_ = next_ = saved_ = {keyframe, local_map, std::uint32_t(segment)};
}

bool RobotIdRenumbering::renumber(const std::string& dds_type, std::vector<std::uint8_t>& cdr) {
    const bool keyframe = dds_type == kKeyframe;
    if ((!keyframe && dds_type != kLocalMap) || !common::is_cdr_le(cdr)) return false;
    common::CdrReader r(cdr.data(), cdr.size());
    std::uint64_t id = 0, scan_index = 0, local_map = 0;
    std::uint32_t segment = 0, revision = 0;
    std::uint8_t finished = 0;
    std::size_t id_at = 0, map_at = 0, segment_at = 0;
    if (!skip_header(r) || !read_at(r, id, id_at)) return false;
    if (keyframe) {
        if (!r.read(scan_index) || !read_at(r, local_map, map_at) ||
            !read_at(r, segment, segment_at))
            return false;
    } else {
        local_map = id;
        map_at = id_at;
        if (!r.read(revision) || !r.read(finished) || !read_at(r, segment, segment_at))
            return false;
    }
    const std::uint64_t new_map = local_map + offsets_.local_map;
    const std::uint32_t new_segment = segment + offsets_.segment;
    if (keyframe) {
        const std::uint64_t new_id = id + offsets_.keyframe;
        if (offsets_.keyframe) write_at(cdr, id_at, new_id);
        next_.keyframe = std::max(next_.keyframe, new_id + 1);
    }
    if (offsets_.local_map) write_at(cdr, map_at, new_map);
    if (offsets_.segment) write_at(cdr, segment_at, new_segment);
    next_.local_map = std::max(next_.local_map, new_map + 1);
    next_.segment = std::max(next_.segment, new_segment + 1);
    return true;
}

void RobotIdRenumbering::save() {
    if (next_ == saved_) return;
    const std::string tmp = file_ + ".tmp";
    std::ostringstream text;
    text << kMagic << "\nkeyframe " << next_.keyframe << "\nlocal_map " << next_.local_map
         << "\nsegment " << next_.segment << "\n";
    const std::string bytes = text.str();
    // On the disk before it replaces the old file (a power cut leaves one of the two whole).
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0) throw common::IoError(tmp, std::strerror(errno));
    const bool written =
        ::write(fd, bytes.data(), bytes.size()) == ssize_t(bytes.size()) && ::fsync(fd) == 0;
    const int err = errno;
    ::close(fd);
    if (!written) throw common::IoError(tmp, std::string("not written: ") + std::strerror(err));
    if (std::rename(tmp.c_str(), file_.c_str()) != 0)
        throw common::IoError(file_, std::string("not replaced: ") + std::strerror(errno));
    saved_ = next_;
}

}  // namespace ltm::link
