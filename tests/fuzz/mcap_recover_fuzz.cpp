// Fuzz target: recovering a damaged MCAP recording (recorder/core/mcap_recover, `ltm record
// --recover`). The input is written to a scratch file and recovered into another.
// Promise: a one-line IoError when the input is not MCAP at all; otherwise an output that is
// complete, verifies clean and holds as many messages as recover() reports.
#include <cstddef>
#include <cstdint>
#include <string>

#include "common/core/io_error.hpp"
#include "fuzz_util.hpp"
#include "recorder/core/mcap_reader.hpp"
#include "recorder/core/mcap_recover.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string in = ltm::fuzz::write_input(data, size, "in.mcap");
    const std::string out = ltm::fuzz::scratch_dir() + "/out.mcap";
    ltm::recorder::RecoverResult result;
    try {
        result = ltm::recorder::recover(in, out);
    } catch (const ltm::common::IoError& e) {
        ltm::fuzz::expect_one_line(e);
        return 0;
    }
    for (const auto& p : result.problems)
        if (p.empty() || p.find_first_of("\n\r") != std::string::npos)
            ltm::fuzz::finding("a problem that is not one line: '" + p + "'");
    try {
        ltm::recorder::McapReader reader(out);
        if (!reader.complete() || !reader.problems().empty())
            ltm::fuzz::finding("the recovered file is not complete: " + reader.problem());
        const ltm::recorder::VerifyReport report = reader.verify();
        if (!report.ok)
            ltm::fuzz::finding(
                "the recovered file does not verify: " +
                (report.problems.empty() ? std::string("?") : report.problems.front()));
        if (report.messages != result.messages)
            ltm::fuzz::finding("recover() reports " + std::to_string(result.messages) +
                               " messages, the output holds " + std::to_string(report.messages));
    } catch (const ltm::common::IoError& e) {
        ltm::fuzz::finding(std::string("the recovered file cannot be read: ") + e.what());
    }
    return 0;
}
