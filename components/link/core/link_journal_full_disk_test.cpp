// The link's journal on a disk that fills up (issue 28, item 4): a refused append leaves the
// journal as it was (nothing half-written, nothing recorded), the same seq can be retried, and
// what was appended before survives a reopen byte for byte. Runs on a small tmpfs (root); skipped
// where mounting is refused.
#include <gtest/gtest.h>

#include <filesystem>

#include "common/core/io_error.hpp"
#include "common/core/small_disk_for_tests.hpp"
#include "link/core/link_journal.hpp"

namespace ltm::link {
namespace {

JournalRecord record(std::uint64_t seq, std::size_t size) {
    JournalRecord r;
    r.seq = seq;
    r.stamp_ns = static_cast<std::int64_t>(seq) * 1000;
    r.topic = "keyframe";
    r.type = "ltm_msgs::msg::dds_::Keyframe_";
    r.payload.resize(size);
    for (std::size_t i = 0; i < size; ++i) r.payload[i] = static_cast<std::uint8_t>(seq * 7 + i);
    return r;
}

// Appends seq, seq+1, ... until the disk refuses one; returns the refused seq.
std::uint64_t fill(LinkJournal& j, std::uint64_t seq, std::string* error) {
    for (;; ++seq) {
        try {
            j.append(record(seq, 3000));
        } catch (const common::IoError& e) {
            *error = e.what();
            return seq;
        }
        if (seq > 100000) ADD_FAILURE() << "the small disk never filled";
    }
}

TEST(JournalFullDisk, ARefusedAppendLeavesTheJournalWholeAndRetriesAfterARelease) {
    common::SmallDisk disk("journal", 64 * 1024);
    if (!disk.mounted()) GTEST_SKIP() << disk.why();
    const std::string dir = disk.path() + "/run";
    // One record a segment: every append opens a new segment file, so the refusals fall on a
    // fresh segment (the case a retry of the same seq once broke).
    const JournalConfig cfg{1, 1ull << 30};
    std::uint64_t refused = 0, last_after = 0;
    {
        LinkJournal j(dir, cfg);
        std::string error;
        refused = fill(j, 1, &error);
        ASSERT_GT(refused, 3u) << error;
        EXPECT_NE(error.find("No space left"), std::string::npos) << error;
        EXPECT_EQ(error.find('\n'), std::string::npos) << error;  // one line
        EXPECT_EQ(j.last_seq(), refused - 1);
        for (int retry = 0; retry < 3; ++retry)  // the sender retries: still refused, still whole
            EXPECT_THROW(j.append(record(refused, 3000)), common::IoError);
        EXPECT_EQ(j.size(), refused - 1);
        // The base station acknowledges half: their segments go and make room for the retry.
        j.release_through(refused / 2);
        ASSERT_NO_THROW(j.append(record(refused, 3000)));
        std::string again;
        last_after = fill(j, refused + 1, &again) - 1;
        // Everything before the released point goes; the retried seq and later stay.
        j.release_through(refused - 1);
        j.sync();
    }
    LinkJournal j(dir, cfg);
    EXPECT_EQ(j.recovery(), "");
    EXPECT_EQ(j.first_seq(), refused);
    EXPECT_EQ(j.last_seq(), last_after);
    ASSERT_EQ(j.size(), last_after - refused + 1);
    for (std::uint64_t s = refused; s <= last_after; ++s) {
        const auto r = j.read_from(s);
        ASSERT_TRUE(r) << s;
        EXPECT_EQ(r->seq, s);
        EXPECT_EQ(r->payload, record(s, 3000).payload) << s;
    }
}

TEST(JournalFullDisk, ARefusalMidSegmentLeavesNoPartialRecord) {
    common::SmallDisk disk("journal_mid", 64 * 1024);
    if (!disk.mounted()) GTEST_SKIP() << disk.why();
    const std::string dir = disk.path() + "/run";
    std::uint64_t refused = 0;
    {
        LinkJournal j(dir, {1ull << 20, 1ull << 30});  // one segment: the refusal is mid-file
        std::string error;
        refused = fill(j, 1, &error);
        ASSERT_GT(refused, 3u) << error;
    }
    LinkJournal j(dir);
    EXPECT_EQ(j.recovery(), "");  // no record cut short: the refused one was taken back
    EXPECT_EQ(j.last_seq(), refused - 1);
    EXPECT_EQ(j.size(), refused - 1);
    EXPECT_EQ(j.read_from(refused - 1)->payload, record(refused - 1, 3000).payload);
}

}  // namespace
}  // namespace ltm::link
