#pragma once
// Samples as serialized CDR bytes (with their 4-byte encapsulation header), for recording and
// replay: what is on the wire goes to a file unchanged and comes back unchanged.
#include <dds/dds.h>

#include <cstddef>
#include <cstdint>
#include <vector>

struct ddsi_sertype;

namespace ltm::runtime {

// The serialization type Cyclone uses for `desc` in the domain of `participant`. Cyclone 0.10 has
// no public getter, so it is probed once per type: a zeroed sample written on a private topic and
// taken back as serdata carries it. Never null for a valid descriptor (throws DdsError).
const ddsi_sertype* sertype_of(dds_entity_t participant, const dds_topic_descriptor_t* desc);

// Writes `size` bytes of serialized CDR through `writer`, whose topic has `type`, with source
// timestamp `source_time` (now when 0).
dds_return_t write_cdr(dds_entity_t writer, const ddsi_sertype* type, const std::uint8_t* cdr,
                       std::size_t size, dds_time_t source_time = 0);

// Takes one sample from `reader` as CDR bytes into `out`; returns 1, 0 (none) or a DDS error.
// `info.valid_data` is false for disposals (then `out` is empty).
int take_cdr(dds_entity_t reader, std::vector<std::uint8_t>& out, dds_sample_info_t& info);

}  // namespace ltm::runtime
