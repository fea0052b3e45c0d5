#pragma once
// info(): what an MCAP file holds (topics, types, counts, duration, rates, size), and a printer.
#include <cstdint>
#include <map>
#include <ostream>
#include <string>
#include <vector>

namespace ltm::recorder {

struct TopicInfo {
    std::uint16_t channel_id = 0;
    std::string topic;
    std::string type;              // schema name, "" without schema
    std::string schema_encoding;   // e.g. "omgidl"
    std::string message_encoding;  // e.g. "cdr"
    std::uint64_t messages = 0;
    double rate_hz = 0.0;  // messages / file duration (0 for a single instant)
};

struct McapInfo {
    std::string path;
    std::uint64_t file_size = 0;  // bytes
    std::string profile, library;
    bool indexed = false;               // read through the summary's chunk index
    bool complete = false;              // intact footer and summary
    std::vector<std::string> problems;  // one line each (first = the one to show)
    std::uint64_t messages = 0;
    std::uint64_t start_time = 0, end_time = 0;  // ns
    double duration_s = 0.0;
    std::uint64_t chunks = 0;
    std::map<std::string, std::uint64_t> chunks_by_compression;  // "zstd" -> count ("" = none)
    std::uint64_t compressed_bytes = 0, uncompressed_bytes = 0;  // chunk records
    std::vector<TopicInfo> topics;                               // sorted by topic, then channel id
};

// Throws common::IoError (one line) when the file cannot be opened or is not MCAP.
McapInfo info(const std::string& path);
void print_info(const McapInfo& info, std::ostream& out);

}  // namespace ltm::recorder
