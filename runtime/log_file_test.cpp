#include "runtime/log_file.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/core/io_error.hpp"
#include "common/core/small_disk_for_tests.hpp"

namespace ltm::runtime {
namespace {

namespace fs = std::filesystem;

std::string read(const std::string& path) {
    std::ifstream in(path);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

// 64 bytes with its '\n'.
std::string line(int i) {
    std::string s = "line " + std::to_string(1000000 + i).substr(1) + " of the host's log";
    s.resize(63, '.');
    return s + "\n";
}

TEST(RotatingLogFile, StaysWithinKeepPlusOneFilesOfMaxSizeAndKeepsTheNewestLines) {
    const fs::path dir = fs::temp_directory_path() / ("ltm_log_file_" + std::to_string(getpid()));
    fs::remove_all(dir);
    HostLogConfig c;
    c.file = (dir / "logs/host.log").string();  // the folder is created
    c.max_mb = 4096.0 / (1 << 20);              // 4 KiB a file
    c.keep = 2;
    {
        RotatingLogFile log(c);
        for (int i = 0; i < 1000; ++i) EXPECT_EQ(log.write(line(i)), "");
    }
    std::uint64_t total = 0;
    int files = 0;
    for (const auto& e : fs::directory_iterator(dir / "logs")) {
        ++files;
        EXPECT_LE(e.file_size(), 4096u) << e.path();
        total += e.file_size();
    }
    EXPECT_EQ(files, 3);  // host.log, host.log.1, host.log.2
    EXPECT_LE(total, 3u * 4096u);
    // The newest line is in the current file, the lines before it in .1; the oldest are gone.
    const std::string now = read(c.file), one = read(c.file + ".1"), two = read(c.file + ".2");
    EXPECT_NE(now.find(line(999)), std::string::npos);
    EXPECT_NE(one.find(line(999 - now.size() / 64)), std::string::npos);
    EXPECT_EQ((now + one + two).find(line(0)), std::string::npos);
    // Whole lines only: every file ends a line.
    EXPECT_EQ(now.back(), '\n');
    EXPECT_EQ(one.size() % 64, 0u);
    // Reopened, it appends to the current file.
    {
        RotatingLogFile log(c);
        log.write(line(1000));
    }
    EXPECT_NE(read(c.file).find(line(1000)), std::string::npos);
    fs::remove_all(dir);
}

TEST(RotatingLogFile, AFolderThatCannotBeMadeIsOneLine) {
    HostLogConfig c;
    c.file = "/proc/ltm_no/host.log";
    try {
        RotatingLogFile log(c);
        FAIL() << "opened";
    } catch (const common::IoError& e) {
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("/proc/ltm_no/host.log"), std::string::npos);
    }
}

TEST(RotatingLogFile, AFullDiskIsSaidOnceAndTheLogGoesOnAfterwards) {
    common::SmallDisk disk("host_log", 16 * 1024);
    if (!disk.mounted()) GTEST_SKIP() << disk.why();
    HostLogConfig c;
    c.file = disk.path() + "/host.log";
    c.max_mb = 1.0;  // larger than the disk: the disk fills before the rotation
    c.keep = 0;
    RotatingLogFile log(c);
    // A filler takes what the log does not: the disk fills while the log writes.
    std::vector<std::string> notes;
    {
        std::ofstream filler(disk.path() + "/filler", std::ios::binary);
        filler << std::string(10 * 1024, 'f');
    }
    for (int i = 0; i < 200; ++i)
        if (std::string n = log.write(line(i)); !n.empty()) notes.push_back(n);
    ASSERT_EQ(notes.size(), 1u);  // said once, not 100 times
    EXPECT_NE(notes[0].find("No space left"), std::string::npos) << notes[0];
    EXPECT_NE(notes[0].find("stderr only"), std::string::npos) << notes[0];
    const std::string before = read(c.file);
    EXPECT_EQ(before.size() % 64, 0u);  // no half line left by a refused write
    fs::remove(disk.path() + "/filler");
    const std::string back = log.write(line(500));
    EXPECT_NE(back.find("takes lines again"), std::string::npos) << back;
    EXPECT_NE(read(c.file).find(line(500)), std::string::npos);
}

}  // namespace
}  // namespace ltm::runtime
