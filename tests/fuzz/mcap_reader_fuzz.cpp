// Fuzz target: reading MCAP recordings (recorder/core: mcap_reader, mcap_scan, message_cursor,
// mcap_info), as `ltm replay` and `ltm info` do. McapReader takes a path, so the input is written
// to a scratch file. Every message is read (all topics, then one topic in a time window), the
// file is verified and summarised.
// Promise: a reader, or a one-line IoError when the bytes are not MCAP at all; every problem found
// while reading is one line; messages refer to known channels and lie inside the input.
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "common/core/io_error.hpp"
#include "fuzz_util.hpp"
#include "recorder/core/mcap_info.hpp"
#include "recorder/core/mcap_reader.hpp"

namespace {

std::uint64_t bytes_sum = 0;  // keeps the reads of every message byte

void check_lines(const std::vector<std::string>& problems) {
    for (const auto& p : problems)
        if (p.empty() || p.find_first_of("\n\r") != std::string::npos)
            ltm::fuzz::finding("a problem that is not one line: '" + p + "'");
}

// Reads every message of the cursor, touching each byte (AddressSanitizer checks the views).
std::uint64_t drain(ltm::recorder::McapReader& reader, const ltm::recorder::ReadOptions& options) {
    std::uint64_t count = 0, sum = 0, last_time = 0;
    ltm::recorder::MessageCursor cursor = reader.messages(options);
    for (ltm::recorder::MessageView m; cursor.next(m);) {
        if (!m.channel) ltm::fuzz::finding("a message without a channel");
        if (m.log_time < last_time) ltm::fuzz::finding("messages out of log-time order");
        if (m.log_time < options.start_time || m.log_time > options.end_time)
            ltm::fuzz::finding("a message outside the time window");
        last_time = m.log_time;
        for (std::size_t i = 0; i < m.size; ++i) sum += m.data[i];
        ++count;
    }
    bytes_sum += sum;
    return count;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string path = ltm::fuzz::write_input(data, size, "in.mcap");
    try {
        ltm::recorder::McapReader reader(path);
        drain(reader, {});
        if (!reader.channels().empty()) {
            ltm::recorder::ReadOptions some;
            some.topics = {reader.channels().begin()->second.topic};
            some.start_time = reader.statistics().message_start_time + 1;
            some.end_time = some.start_time + 1000;
            some.check_crcs = false;
            drain(reader, some);
        }
        check_lines(reader.problems());
        const ltm::recorder::VerifyReport report = reader.verify();
        check_lines(report.problems);
        if (report.ok && !report.problems.empty()) ltm::fuzz::finding("verify() ok with problems");
    } catch (const ltm::common::IoError& e) {
        ltm::fuzz::expect_one_line(e);
    }
    try {
        const ltm::recorder::McapInfo info = ltm::recorder::info(path);
        check_lines(info.problems);
        std::ostringstream out;
        ltm::recorder::print_info(info, out);
    } catch (const ltm::common::IoError& e) {
        ltm::fuzz::expect_one_line(e);
    }
    return 0;
}
