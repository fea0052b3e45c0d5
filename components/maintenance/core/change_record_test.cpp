// Change records: written and read back exactly; any damage, truncation or other version refused
// with one line; the summary and the PLY; a ledger left as it was by a damaged record.
#include "maintenance/core/change_record.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/core/io_error.hpp"
#include "maintenance/core/change_ledger.hpp"
#include "maintenance/core/change_report.hpp"
#include "maintenance/core/change_set_expect.hpp"

namespace ltm::maintenance {
namespace {

namespace fs = std::filesystem;

SegmentChange change(std::uint64_t id, ChangeReason reason, std::vector<Eigen::Vector3f> voxels) {
    SegmentChange c;
    c.id = id;
    c.reason = reason;
    c.region = {id % 2 ? -1 : 3, 2};
    c.voxels = std::move(voxels);
    c.bbox_min = c.bbox_max = c.voxels.front();
    Eigen::Vector3f sum = Eigen::Vector3f::Zero();
    for (const Eigen::Vector3f& p : c.voxels) {
        c.bbox_min = c.bbox_min.cwiseMin(p);
        c.bbox_max = c.bbox_max.cwiseMax(p);
        sum += p;
    }
    c.centroid = sum / float(c.voxels.size());
    c.first_seen = 0.1 * double(id);
    c.last_seen = c.first_seen + 3.7;
    c.score = 0.1 + 0.2 * double(id);
    c.judged = std::uint32_t(c.voxels.size() - 1);
    return c;
}

// A small pass: a car that moved, a box that vanished, a container that is new.
ChangeSet sample(std::uint32_t session = 1) {
    ChangeSet s;
    s.session = session;
    s.map_time = 123.456789;
    s.voxel_size = 0.25f;
    s.changes.push_back(
        change(7, ChangeReason::kMoving, {{1.125f, 2.375f, 0.625f}, {1.375f, 2.375f, 0.625f}}));
    s.changes.push_back(change(8, ChangeReason::kVanished, {{-5.125f, 0.125f, 1.875f}}));
    s.changes.push_back(
        change(9, ChangeReason::kNew, {{10.125f, -3.375f, 0.375f}, {10.125f, -3.125f, 0.375f}}));
    s.voxels_before = 90210;
    s.voxels_removed = 3;
    s.voxels_judged = 4567;
    s.segments = 42;
    s.ground_voxels = 30000;
    s.time_ms = 12.5;
    return s;
}

// The decode of `bytes` must be refused with one FormatError line naming the source.
void expect_refused(const std::string& bytes, const std::string& what) {
    try {
        decode_change_record(bytes, "rec.ltmc");
        ADD_FAILURE() << what << ": accepted";
    } catch (const common::FormatError& e) {
        const std::string m = e.what();
        EXPECT_EQ(m.find('\n'), std::string::npos) << what << ": " << m;
        EXPECT_EQ(m.rfind("rec.ltmc: ", 0), 0u) << what << ": " << m;
    }
}

class ChangeRecordFiles : public ::testing::Test {
  protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() /
               ("ltm_change_record_" + std::to_string(::getpid()) + "_" +
                ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }
    std::string path(const std::string& name) const { return (dir_ / name).string(); }
    fs::path dir_;
};

TEST(ChangeRecord, RoundTripIsExact) {
    const ChangeSet s = sample();
    const std::string bytes = encode_change_record(s);
    expect_same_changes(s, decode_change_record(bytes, "rec.ltmc"));
    EXPECT_EQ(encode_change_record(decode_change_record(bytes, "rec.ltmc")), bytes);
    // An empty pass too.
    ChangeSet empty;
    empty.voxel_size = 0.5f;
    expect_same_changes(empty, decode_change_record(encode_change_record(empty), "empty.ltmc"));
}

TEST(ChangeRecord, EverySingleByteCorruptionIsRefused) {
    const std::string bytes = encode_change_record(sample());
    ASSERT_LT(bytes.size(), 1000u);  // small: every byte is tried
    for (std::size_t i = 0; i < bytes.size(); ++i) {
        for (const unsigned char flip : {0x01, 0x80, 0xff}) {
            std::string damaged = bytes;
            damaged[i] = static_cast<char>(static_cast<unsigned char>(damaged[i]) ^ flip);
            expect_refused(damaged, "byte " + std::to_string(i) + " ^ " + std::to_string(flip));
        }
    }
}

TEST(ChangeRecord, EveryTruncationAndAppendIsRefused) {
    const std::string bytes = encode_change_record(sample());
    for (std::size_t n = 0; n < bytes.size(); ++n)
        expect_refused(bytes.substr(0, n), "first " + std::to_string(n) + " bytes");
    expect_refused(bytes + '\0', "one byte more");
}

TEST(ChangeRecord, OtherVersionOrKindIsRefusedByName) {
    std::string bytes = encode_change_record(sample());
    std::string v2 = bytes;
    v2[8] = 2;
    try {
        decode_change_record(v2, "rec.ltmc");
        FAIL() << "version 2 accepted";
    } catch (const common::FormatError& e) {
        EXPECT_EQ(std::string(e.what()),
                  "rec.ltmc: format version at byte 8: format 2 is not supported (this build "
                  "reads 1)");
    }
    std::string other = bytes;
    std::memcpy(other.data(), "LTM-LMAP", 8);
    try {
        decode_change_record(other, "rec.ltmc");
        FAIL() << "a local map's magic accepted";
    } catch (const common::FormatError& e) {
        EXPECT_EQ(std::string(e.what()), "rec.ltmc: magic at byte 0: not an ltm change record");
    }
}

TEST_F(ChangeRecordFiles, FileRoundTripAndMissingFile) {
    const ChangeSet s = sample();
    write_change_record(path("c.ltmc"), s);
    expect_same_changes(s, read_change_record(path("c.ltmc")));
    EXPECT_FALSE(fs::exists(path("c.ltmc.tmp")));
    try {
        read_change_record(path("none.ltmc"));
        FAIL();
    } catch (const common::IoError& e) {
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("none.ltmc"), std::string::npos);
    }
}

TEST_F(ChangeRecordFiles, SummaryAndPly) {
    const ChangeSet s = sample(2);
    std::ostringstream text;
    write_change_summary(text, s, 3);
    const std::string t = text.str();
    EXPECT_EQ(t.rfind("session 2 pass 3 at 123.5 s: 1 moving, 1 vanished, 1 new segments; 3 of "
                      "90210 voxels removed",
                      0),
              0u)
        << t;
    EXPECT_NE(t.find("  moving   id 7  centre 1.25 2.38 0.62"), std::string::npos) << t;
    EXPECT_NE(t.find("  new      id 9"), std::string::npos) << t;
    EXPECT_EQ(std::count(t.begin(), t.end(), '\n'), 4);

    write_change_ply(path("c.ply"), s);
    std::ifstream in(path("c.ply"), std::ios::binary);
    const std::string ply((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::size_t end = ply.find("end_header\n");
    ASSERT_NE(end, std::string::npos);
    EXPECT_NE(ply.find("element vertex 5\n"), std::string::npos);
    const std::size_t body = end + 11;
    ASSERT_EQ(ply.size(), body + 5 * 15);
    // Vertex 0: the moving car's first voxel, red; vertex 3: the new container's, green.
    float x = 0;
    std::memcpy(&x, ply.data() + body, 4);
    EXPECT_EQ(x, 1.125f);
    EXPECT_GT((unsigned char)ply[body + 12], (unsigned char)ply[body + 13]);
    EXPECT_LT((unsigned char)ply[body + 3 * 15 + 12], (unsigned char)ply[body + 3 * 15 + 13]);
}

// The run's PLY from its passes' records, read one at a time, is the PLY of all their changes
// together (the maintenance component writes it so at the session's end, keeping none in memory).
TEST_F(ChangeRecordFiles, ThePlyOfTheRecordsIsThePlyOfTheirChangesTogether) {
    ChangeSet first = sample(1), second = sample(1);
    for (SegmentChange& c : second.changes)
        for (Eigen::Vector3f& v : c.voxels) v += Eigen::Vector3f(10.0f, 0.0f, 0.0f);
    write_change_record(path("p0.ltmc"), first);
    write_change_record(path("p1.ltmc"), second);
    ChangeSet all = first;
    all.append(second);
    write_change_ply(path("all.ply"), all);
    write_change_ply(path("records.ply"), {path("p0.ltmc"), path("p1.ltmc")});
    const auto read = [](const std::string& p) {
        std::ifstream in(p, std::ios::binary);
        return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    };
    const std::string ply = read(path("records.ply"));
    EXPECT_NE(ply.find("element vertex 10\n"), std::string::npos);
    EXPECT_EQ(ply, read(path("all.ply")));
    // A damaged record: one line, and the PLY written before stays as it was.
    std::ofstream(path("p1.ltmc"), std::ios::binary | std::ios::trunc) << "not a record";
    EXPECT_ANY_THROW(write_change_ply(path("records.ply"), {path("p0.ltmc"), path("p1.ltmc")}));
    EXPECT_EQ(read(path("records.ply")), ply);
}

// The map untouched: a ledger that applied good records meets a damaged one (every truncation
// and a flipped byte in each section) and is exactly as before; a record of another voxel size or
// an earlier session is refused the same way.
TEST_F(ChangeRecordFiles, DamagedRecordLeavesTheLedgerUntouched) {
    ChangeLedger ledger(0.25f);
    write_change_record(path("s1.ltmc"), sample(1));
    ledger.apply_record(path("s1.ltmc"));
    EXPECT_EQ(ledger.records(), 1u);
    EXPECT_EQ(ledger.removed_voxels(), 3u);
    EXPECT_EQ(ledger.added_voxels(), 2u);
    EXPECT_TRUE(ledger.removed({1.2f, 2.4f, 0.7f}));
    EXPECT_TRUE(ledger.added({10.2f, -3.3f, 0.4f}));
    EXPECT_FALSE(ledger.removed({10.2f, -3.3f, 0.4f}));
    const ChangeLedger before = ledger;

    // Session 2 adds the moving car's cells back and removes the container: what a good record
    // would do, so that a refused one visibly did not.
    ChangeSet next = sample(2);
    next.changes[0].reason = ChangeReason::kNew;
    next.changes[2].reason = ChangeReason::kVanished;
    const std::string bytes = encode_change_record(next);
    std::vector<std::string> damaged;
    for (std::size_t n = 0; n < bytes.size(); n += 7) damaged.push_back(bytes.substr(0, n));
    for (std::size_t i = 0; i < bytes.size(); i += 5) {
        damaged.push_back(bytes);
        damaged.back()[i] = static_cast<char>(damaged.back()[i] ^ 0x10);
    }
    for (std::size_t k = 0; k < damaged.size(); ++k) {
        std::ofstream(path("bad.ltmc"), std::ios::binary) << damaged[k];
        try {
            ledger.apply_record(path("bad.ltmc"));
            ADD_FAILURE() << "damaged record " << k << " applied";
        } catch (const common::FormatError& e) {
            EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
        }
        ASSERT_TRUE(ledger == before) << "damaged record " << k << " changed the ledger";
    }
    ChangeSet coarse = next;
    coarse.voxel_size = 0.5f;
    write_change_record(path("coarse.ltmc"), coarse);
    try {
        ledger.apply_record(path("coarse.ltmc"));
        FAIL();
    } catch (const common::FormatError& e) {
        EXPECT_NE(std::string(e.what()).find("voxel size 0.500000 m differs"), std::string::npos)
            << e.what();
    }
    write_change_record(path("s0.ltmc"), sample(0));
    EXPECT_THROW(ledger.apply_record(path("s0.ltmc")), common::FormatError);
    EXPECT_TRUE(ledger == before);

    // The good record applies.
    write_change_record(path("s2.ltmc"), next);
    ledger.apply_record(path("s2.ltmc"));
    EXPECT_TRUE(ledger.added({1.2f, 2.4f, 0.7f}));
    EXPECT_TRUE(ledger.removed({10.2f, -3.3f, 0.4f}));
    EXPECT_EQ(ledger.records(), 2u);
}

}  // namespace
}  // namespace ltm::maintenance
