#pragma once
// What of an offered version must cross the link (site_sync, issue 26): a file the robot holds
// (same size and hash, held_files.hpp) is taken from its disk; every other file is cut into the
// offer's chunks, which the robot asks for.
#include <cstdint>
#include <string>
#include <vector>

#include "site/core/held_files.hpp"
#include "site/core/version_files.hpp"

namespace ltm::site_sync {

struct TransferPlan {
    // Per file of the offer: the robot's own copy, or "" when the file must be sent.
    std::vector<std::string> local_source;
    std::vector<ChunkRef> chunks;  // every chunk to send, in file and chunk order
    std::size_t files_to_send = 0;
    std::uint64_t bytes_to_send = 0;  // the sent files' sizes
    std::uint64_t bytes_total = 0;    // the version's
    bool sends(std::size_t file) const { return local_source[file].empty(); }
};

TransferPlan plan_transfer(const VersionOffer& offer, const HeldFiles& held);

}  // namespace ltm::site_sync
