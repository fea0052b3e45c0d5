#include "link/core/link_journal.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "common/core/io_error.hpp"

namespace ltm::link {
namespace {

namespace fs = std::filesystem;

class JournalTest : public ::testing::Test {
  protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() /
               ("ltm_journal_" + std::to_string(::getpid()) + "_" +
                ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }
    static JournalRecord record(std::uint64_t seq, std::size_t size = 100) {
        JournalRecord r;
        r.seq = seq;
        r.stamp_ns = static_cast<std::int64_t>(seq) * 1000;
        r.topic = seq % 2 ? "keyframe" : "local_map";
        r.type = "ltm_msgs::msg::dds_::Keyframe_";
        r.payload.resize(size);
        for (std::size_t i = 0; i < size; ++i) r.payload[i] = static_cast<std::uint8_t>(seq + i);
        return r;
    }
    std::vector<std::string> segment_files() const {
        std::vector<std::string> out;
        for (const auto& e : fs::directory_iterator(dir_))
            if (e.path().extension() == ".ltmj") out.push_back(e.path().string());
        std::sort(out.begin(), out.end());
        return out;
    }
    fs::path dir_;
};

TEST_F(JournalTest, RecordsReadBackAfterReopen) {
    {
        LinkJournal j(dir_.string(), {1000, 1ull << 30});
        for (std::uint64_t s = 1; s <= 30; ++s) EXPECT_EQ(j.append(record(s)), 0u);
        j.sync();
        EXPECT_EQ(j.size(), 30u);
        EXPECT_GT(segment_files().size(), 2u);  // several segments of ~1000 bytes
    }
    LinkJournal j(dir_.string());
    EXPECT_EQ(j.recovery(), "");
    ASSERT_EQ(j.size(), 30u);
    EXPECT_EQ(j.first_seq(), 1u);
    EXPECT_EQ(j.last_seq(), 30u);
    for (std::uint64_t s = 1; s <= 30; ++s) {
        const auto r = j.read_from(s);
        ASSERT_TRUE(r);
        const JournalRecord want = record(s);
        EXPECT_EQ(r->seq, s);
        EXPECT_EQ(r->stamp_ns, want.stamp_ns);
        EXPECT_EQ(r->topic, want.topic);
        EXPECT_EQ(r->type, want.type);
        EXPECT_EQ(r->payload, want.payload);
    }
    EXPECT_FALSE(j.read_from(31));
    // New records go after the old ones.
    j.append(record(31));
    EXPECT_EQ(j.read_from(31)->seq, 31u);
    EXPECT_THROW(j.append(record(31)), std::invalid_argument);
}

TEST_F(JournalTest, GapsAreAllowedAndReadFromSkipsThem) {
    LinkJournal j(dir_.string());
    j.append(record(3));
    j.append(record(7));
    EXPECT_EQ(j.read_from(1)->seq, 3u);
    EXPECT_EQ(j.read_from(4)->seq, 7u);
}

TEST_F(JournalTest, ReleasedRecordsStayForgottenAndTheirSegmentsGo) {
    {
        LinkJournal j(dir_.string(), {1000, 1ull << 30});
        for (std::uint64_t s = 1; s <= 30; ++s) j.append(record(s));
        const std::size_t before = segment_files().size();
        j.release_through(20);
        EXPECT_EQ(j.first_seq(), 21u);
        EXPECT_EQ(j.size(), 10u);
        EXPECT_LT(segment_files().size(), before);
    }
    LinkJournal j(dir_.string());
    EXPECT_EQ(j.first_seq(), 21u);
    EXPECT_EQ(j.last_seq(), 30u);
    j.release_through(30);
    EXPECT_TRUE(j.empty());
    // Seqs keep increasing after everything was released and the journal reopened.
    LinkJournal k(dir_.string());
    EXPECT_TRUE(k.empty());
    EXPECT_EQ(k.last_seq(), 30u);
    EXPECT_THROW(k.append(record(30)), std::invalid_argument);
    k.append(record(31));
}

TEST_F(JournalTest, BoundDropsTheOldestSegments) {
    LinkJournal j(dir_.string(), {2000, 5000});
    std::size_t dropped = 0;
    for (std::uint64_t s = 1; s <= 100; ++s) dropped += j.append(record(s));
    EXPECT_GT(dropped, 0u);
    EXPECT_LE(j.bytes(), 5000u + 2000u);
    EXPECT_EQ(j.last_seq(), 100u);
    EXPECT_EQ(j.first_seq(), 100u - j.size() + 1);
    EXPECT_EQ(dropped + j.size(), 100u);
}

TEST_F(JournalTest, ACutOffTailIsReportedAndTheRestKept) {
    {
        LinkJournal j(dir_.string());
        for (std::uint64_t s = 1; s <= 5; ++s) j.append(record(s));
    }
    const std::string seg = segment_files().back();
    const auto size = fs::file_size(seg);
    fs::resize_file(seg, size - 30);  // a crash in the middle of the last record
    {
        LinkJournal j(dir_.string());
        EXPECT_NE(j.recovery().find("cut short"), std::string::npos) << j.recovery();
        EXPECT_EQ(j.last_seq(), 4u);
        j.append(record(5));  // the lost record can be written again
        EXPECT_EQ(j.read_from(5)->payload, record(5).payload);
    }
    LinkJournal j(dir_.string());
    EXPECT_EQ(j.recovery(), "");
    EXPECT_EQ(j.size(), 5u);
}

TEST_F(JournalTest, DamagedBytesEndTheSegment) {
    {
        LinkJournal j(dir_.string());
        for (std::uint64_t s = 1; s <= 5; ++s) j.append(record(s, 50));
    }
    const std::string seg = segment_files().back();
    {
        std::fstream f(seg, std::ios::in | std::ios::out | std::ios::binary);
        f.seekp(3 * (12 + 20 + 8 + 30 + 50) + 40);  // inside record 4's payload
        f.put('\x5a');
    }
    LinkJournal j(dir_.string());
    EXPECT_NE(j.recovery().find("damaged"), std::string::npos) << j.recovery();
    EXPECT_EQ(j.last_seq(), 3u);
}

TEST_F(JournalTest, GarbageFileIsCutNotACrash) {
    fs::create_directories(dir_);
    {
        std::ofstream f(dir_ / "seg-00000000000000000001.ltmj", std::ios::binary);
        f << "this is not a journal";
    }
    LinkJournal j(dir_.string());
    EXPECT_NE(j.recovery().find("not a journal record"), std::string::npos);
    EXPECT_TRUE(j.empty());
}

TEST_F(JournalTest, UnwritableFolderIsOneLineError) {
    fs::create_directories(dir_);
    std::ofstream(dir_ / "file") << "x";
    try {
        LinkJournal j((dir_ / "file" / "sub").string());
        FAIL() << "no error";
    } catch (const common::IoError& e) {
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    }
}

}  // namespace
}  // namespace ltm::link
