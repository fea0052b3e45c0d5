#pragma once
// JSON manifests of MCAP content, compared by the independent-reader test (@mcap/core): every
// schema, channel and message (times as decimal strings, bytes as hex) in log-time order.
#include <ostream>
#include <string>

#include "recorder/core/compression.hpp"
#include "recorder/core/mcap_reader.hpp"

namespace ltm::recorder::tools {

// What `reader` reads: summary/scan schemas and channels, then every message in log-time order.
void write_manifest(McapReader& reader, std::ostream& out);

struct TestFileOptions {
    Compression compression = Compression::kZstd;
    std::size_t chunk_size = 64 * 1024;  // bytes: small, so the file has many chunks
    std::size_t messages = 600;
};
// Writes a deterministic file (3 channels, 2 omgidl schemas, messages of 0..30000 bytes written
// slightly out of log-time order, unique log times) and the manifest of what it wrote.
void write_test_file(const std::string& path, const TestFileOptions& options,
                     std::ostream& manifest);

std::string json_escape(const std::string& s);
std::string hex(const void* data, std::size_t size);

}  // namespace ltm::recorder::tools
