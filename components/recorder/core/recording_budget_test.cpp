#include "recorder/core/recording_budget.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "recorder/core/test_util.hpp"

namespace ltm::recorder {
namespace {

namespace fs = std::filesystem;

// Writes `bytes` bytes and dates the file `age_s` seconds back.
void make_file(const std::string& path, std::size_t bytes, int age_s) {
    fs::create_directories(fs::path(path).parent_path());
    std::ofstream(path, std::ios::binary) << std::string(bytes, 'x');
    fs::last_write_time(path, fs::file_time_type::clock::now() - std::chrono::seconds(age_s));
}

std::set<std::string> names_under(const std::string& dir) {
    std::set<std::string> out;
    for (const auto& e : fs::recursive_directory_iterator(dir))
        if (e.is_regular_file()) out.insert(fs::relative(e.path(), dir).string());
    return out;
}

TEST(RecordingBudget, OldestWholeFilesGoFirstUntilTheSizeHolds) {
    test::TempDir tmp("budget_size");
    const std::string d = tmp.file("recordings");
    make_file(d + "/day1/lifelong.mcap", 400, 400);
    make_file(d + "/day2/lifelong.mcap", 300, 300);
    make_file(d + "/day3/lifelong.mcap", 200, 200);
    make_file(d + "/day3/notes.txt", 5000, 500);   // not a recording: never counted or removed
    make_file(d + "/day4/lifelong.mcap", 100, 0);  // being written
    RecordingBudget b;
    b.max_total_bytes = 350;
    const BudgetResult r = enforce_budget(d, b, {d + "/day4/lifelong.mcap"});
    EXPECT_TRUE(r.error.empty()) << r.error;
    // Oldest first: day1 (400) and day2 (300) go, 300 bytes remain (day3 + day4).
    ASSERT_EQ(r.removed.size(), 2u);
    EXPECT_EQ(fs::path(r.removed[0]).parent_path().filename(), "day1");
    EXPECT_EQ(fs::path(r.removed[1]).parent_path().filename(), "day2");
    EXPECT_EQ(r.removed_bytes, 700u);
    EXPECT_EQ(r.kept_bytes, 300u);
    EXPECT_EQ(r.kept_files, 2u);
    EXPECT_FALSE(r.protected_over_budget);
    EXPECT_EQ(names_under(d), (std::set<std::string>{"day3/lifelong.mcap", "day3/notes.txt",
                                                     "day4/lifelong.mcap"}));
    EXPECT_NE(describe(r).find("removed 2 recordings"), std::string::npos) << describe(r);
}

TEST(RecordingBudget, TheFileBeingWrittenIsNeverRemovedEvenWhenOldestOrOverBudget) {
    test::TempDir tmp("budget_protect");
    const std::string d = tmp.file("recordings");
    make_file(d + "/a.mcap", 1000, 900);  // oldest, and being written (a long recording)
    make_file(d + "/b.mcap", 10, 100);
    RecordingBudget b;
    b.max_total_bytes = 500;
    const BudgetResult r = enforce_budget(d, b, {d + "/./a.mcap"});  // another spelling of it
    ASSERT_EQ(r.removed.size(), 1u);
    EXPECT_EQ(fs::path(r.removed[0]).filename(), "b.mcap");
    EXPECT_TRUE(fs::exists(d + "/a.mcap"));
    EXPECT_TRUE(r.protected_over_budget);
    EXPECT_EQ(r.kept_bytes, 1000u);
}

TEST(RecordingBudget, KeepNewestBoundsTheCount) {
    test::TempDir tmp("budget_count");
    const std::string d = tmp.file("recordings");
    for (int i = 0; i < 6; ++i) make_file(d + "/r" + std::to_string(i) + ".mcap", 10, 100 - i);
    RecordingBudget b;
    b.keep_newest = 2;
    const BudgetResult r = enforce_budget(d, b, {});
    EXPECT_EQ(r.removed.size(), 4u);
    EXPECT_EQ(names_under(d), (std::set<std::string>{"r4.mcap", "r5.mcap"}));
    // Within both bounds: nothing more goes.
    EXPECT_TRUE(enforce_budget(d, b, {}).removed.empty());
}

TEST(RecordingBudget, NoBoundsAndAMissingFolderRemoveNothing) {
    test::TempDir tmp("budget_none");
    const std::string d = tmp.file("recordings");
    EXPECT_TRUE(enforce_budget(d, RecordingBudget{}, {}).removed.empty());
    make_file(d + "/a.mcap", 1 << 16, 10);
    const BudgetResult r = enforce_budget(d, RecordingBudget{}, {});
    EXPECT_TRUE(r.removed.empty());
    EXPECT_EQ(r.kept_files, 1u);
    EXPECT_TRUE(fs::exists(d + "/a.mcap"));
}

}  // namespace
}  // namespace ltm::recorder
