// Fuzz target: the link's payload codec (link/core/payload_codec). The first byte picks the DDS
// type (bit 0..1: Keyframe_, LocalMap_, another) and the direction (bit 7): decoding the rest as a
// wire form gives CDR or a one-line std::runtime_error, and a CDR it gives encodes and decodes to
// itself; encoding the rest as CDR (any bytes) always decodes back to exactly those bytes.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "fuzz_util.hpp"
#include "link/core/payload_codec.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size == 0) return 0;
    static const std::string types[] = {
        "ltm_msgs::msg::dds_::Keyframe_", "ltm_msgs::msg::dds_::LocalMap_",
        "some_msgs::msg::dds_::Other_", "ltm_msgs::msg::dds_::LocalMap_"};
    const std::string& type = types[data[0] & 3];
    const std::vector<std::uint8_t> rest(data + 1, data + size);
    if (data[0] & 0x80) {
        const std::vector<std::uint8_t> wire = ltm::link::encode_payload(type, rest);
        if (ltm::link::decode_payload(type, wire) != rest)
            ltm::fuzz::finding("decode(encode(cdr)) is not the cdr");
        return 0;
    }
    std::vector<std::uint8_t> cdr;
    try {
        cdr = ltm::link::decode_payload(type, rest);
    } catch (const std::runtime_error& e) {
        ltm::fuzz::expect_one_line(e);
        return 0;
    }
    if (ltm::link::decode_payload(type, ltm::link::encode_payload(type, cdr)) != cdr)
        ltm::fuzz::finding("a decoded cdr does not survive encode and decode");
    return 0;
}
