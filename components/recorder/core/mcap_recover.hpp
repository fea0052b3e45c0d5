#pragma once
// recover(): rewrites an MCAP file that was cut short (kill -9, power loss, full disk) or damaged
// into a complete, indexed file holding every message that is still intact.
#include <cstdint>
#include <string>
#include <vector>

#include "recorder/core/mcap_writer.hpp"

namespace ltm::recorder {

struct RecoverResult {
    std::uint64_t messages = 0;         // messages written to the output
    std::uint64_t chunks = 0;           // chunks written to the output
    std::vector<std::string> problems;  // what was wrong with the input (one line each)
};

// Reads `in` (by linear scan when it has no intact summary) and writes its messages, schemas and
// channels (same ids, times, sequence numbers and bytes) to `out` in log-time order. The output
// keeps the input's compression unless keep_compression is false (then config.compression).
// Throws common::IoError when `in` is not MCAP, `out` cannot be written, or in == out.
RecoverResult recover(const std::string& in, const std::string& out, McapWriterConfig config = {},
                      bool keep_compression = true);

}  // namespace ltm::recorder
