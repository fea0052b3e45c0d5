#pragma once
// The link's wire form of one message (issue 15): the message's serialized CDR, compressed
// losslessly with zstd after a transform that knows its layout where that pays.
//
//   byte 0       codec (PayloadCodec)
//   bytes 1-4    size of the CDR [B], little-endian
//   then         kStored: the CDR; kZstd: a zstd frame of it; kShuffled: the byte-shuffled ranges
//                (count, then offset, length, stride of each) and a zstd frame of the CDR with
//                those ranges shuffled; kLocalMap: a zstd frame of the map's columns
//
// kShuffled (keyframes; any type whose float arrays are found): the point cloud's bytes grouped
// by byte position within a point (all x low bytes, ..., all intensity high bytes), the
// descriptor's floats by byte position, so that zstd sees runs of similar bytes. kLocalMap: the
// voxels' fields as columns, each the residual of a prediction (local_map_columns.hpp) grouped by
// byte position. Anything else, or a message that does not parse as its type, is plain zstd;
// a message that zstd does not shrink is stored. The decoder needs no schema for kShuffled, so an
// older base station reads any newer robot's keyframes; an unknown codec byte is an error.
#include <cstdint>
#include <string>
#include <vector>

namespace ltm::link {

struct PayloadCodecConfig {
    int level = 3;  // zstd level (1..19): higher is smaller and slower to encode, not to decode
};

enum class PayloadCodec : std::uint8_t {
    kStored = 0,    // the CDR as it is
    kZstd = 1,      // zstd of the CDR
    kShuffled = 2,  // zstd of the CDR with ranges byte-shuffled (keyframes)
    kLocalMap = 3,  // zstd of a LocalMap_'s columns
};

// The wire form of one message's serialized CDR (with its 4-byte encapsulation header) of DDS type
// `dds_type` (e.g. "ltm_msgs::msg::dds_::Keyframe_"). Lossless:
// decode_payload(dds_type, encode_payload(dds_type, x)) == x. Throws std::runtime_error (one line)
// only for a config it cannot use (level out of range) or a CDR over 1 GiB.
std::vector<std::uint8_t> encode_payload(const std::string& dds_type,
                                         const std::vector<std::uint8_t>& cdr,
                                         const PayloadCodecConfig& config = {});

// The CDR back. Throws std::runtime_error with one line on a malformed or truncated payload
// (never crashes, never allocates more than the size the payload states, at most 1 GiB).
std::vector<std::uint8_t> decode_payload(const std::string& dds_type,
                                         const std::vector<std::uint8_t>& wire);

// The codec of a wire form; throws std::runtime_error when it is empty or names no codec.
PayloadCodec payload_codec(const std::vector<std::uint8_t>& wire);
const char* codec_name(PayloadCodec codec);

}  // namespace ltm::link
