#include "bench/budget/cdr_stamp.hpp"

namespace ltm::bench {

std::optional<double> cdr_header_stamp(const std::uint8_t* d, std::size_t size) {
    if (size < 12) return {};
    const bool little = (d[1] & 1) != 0;  // CDR_LE 0x0001, CDR2_LE 0x0007, ...
    auto u32 = [&](std::size_t at) {
        return little ? std::uint32_t(d[at]) | std::uint32_t(d[at + 1]) << 8 |
                            std::uint32_t(d[at + 2]) << 16 | std::uint32_t(d[at + 3]) << 24
                      : std::uint32_t(d[at + 3]) | std::uint32_t(d[at + 2]) << 8 |
                            std::uint32_t(d[at + 1]) << 16 | std::uint32_t(d[at]) << 24;
    };
    const auto sec = std::int32_t(u32(4));
    const std::uint32_t nanosec = u32(8);
    return double(sec) + 1e-9 * double(nanosec);
}

}  // namespace ltm::bench
