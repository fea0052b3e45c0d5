// Fuzz target: reading a change record (maintenance/core/change_record) and applying it to a
// ledger (maintenance/core/change_ledger). Promise: the decoded ChangeSet, or a one-line
// FormatError; what decodes re-encodes to the same bytes (one description for both directions);
// a record the ledger refuses leaves it exactly as it was.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "common/core/io_error.hpp"
#include "fuzz_util.hpp"
#include "maintenance/core/change_ledger.hpp"
#include "maintenance/core/change_record.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string bytes(reinterpret_cast<const char*>(data), size);
    ltm::maintenance::ChangeSet changes;
    try {
        changes = ltm::maintenance::decode_change_record(bytes, "changes.ltmc");
    } catch (const ltm::common::FormatError& e) {
        ltm::fuzz::expect_one_line(e);
        return 0;
    }
    if (ltm::maintenance::encode_change_record(changes) != bytes)
        ltm::fuzz::finding("encode(decode(bytes)) changes the bytes");
    ltm::maintenance::ChangeLedger ledger(0.25f);
    const ltm::maintenance::ChangeLedger before = ledger;
    try {
        ledger.apply(changes);
    } catch (const std::invalid_argument& e) {
        ltm::fuzz::expect_one_line(e);
        if (ledger != before) ltm::fuzz::finding("a refused record changed the ledger");
    }
    return 0;
}
