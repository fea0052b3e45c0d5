#pragma once
// A LocalMap_'s CDR (idl/ltm_msgs/msg/LocalMap.idl) rearranged as columns for compression: the
// bytes before the voxels as they are, then each voxel field of every voxel in turn, every column
// grouped by byte position (all low bytes, ..., all high bytes), then the `seen` indices and
// whatever follows the voxels. Fields are stored as what a prediction leaves: ix, iy, iz as
// differences to the previous voxel; the centre as the difference of its float bits to its
// cell's middle; the normal's z to sqrt(1 - x^2 - y^2); created and last_seen as indices into
// the map's observation_times when they are one of them. Integer bijections throughout: lossless,
// from_columns(to_columns(cdr)) == cdr whenever to_columns succeeds.
#include <cstdint>
#include <optional>
#include <vector>

namespace ltm::link {

// The column form; nullopt when `cdr` is not a LocalMap_ in CDR_LE, or has padding bytes that are
// not zero (it would not come back byte for byte).
std::optional<std::vector<std::uint8_t>> local_map_to_columns(const std::vector<std::uint8_t>& cdr);

// The CDR back; throws std::runtime_error (one line) when `columns` is not a column form.
std::vector<std::uint8_t> local_map_from_columns(const std::vector<std::uint8_t>& columns);

// Byte-plane shuffle of `n` elements of `stride` bytes: byte j of element i goes to j * n + i.
void shuffle_bytes(const std::uint8_t* in, std::size_t n, std::size_t stride, std::uint8_t* out);
void unshuffle_bytes(const std::uint8_t* in, std::size_t n, std::size_t stride, std::uint8_t* out);

}  // namespace ltm::link
