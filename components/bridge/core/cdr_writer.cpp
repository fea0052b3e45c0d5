#include "bridge/core/cdr_writer.hpp"

namespace ltm::bridge {

#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ != __ORDER_LITTLE_ENDIAN__
#error "CdrWriter writes the host's byte order and declares it little endian"
#endif

void CdrWriter::string(const std::string& s) {
    u32(static_cast<std::uint32_t>(s.size() + 1));
    buffer_.insert(buffer_.end(), s.begin(), s.end());
    buffer_.push_back(0);
}

void CdrWriter::bytes(const void* data, std::size_t size) {
    const auto* p = static_cast<const std::uint8_t*>(data);
    buffer_.insert(buffer_.end(), p, p + size);
}

}  // namespace ltm::bridge
