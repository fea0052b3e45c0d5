// SITE/lock: a second live session on a site is refused (naming the holder's pid); a holder
// killed with SIGKILL leaves no stale lock.
#include "map/core/site_lock.hpp"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>

#include "common/core/file_io.hpp"
#include "common/core/io_error.hpp"

namespace ltm::map {
namespace {

namespace fs = std::filesystem;

std::string lock_path(const std::string& name) {
    const fs::path p = fs::path(LTM_BINARY_DIR) / "site_test" / name;
    fs::remove_all(p);
    return (p / "lock").string();
}

std::string refusal(const std::string& path) {
    try {
        SiteLock again(path);
    } catch (const common::IoError& e) {
        return e.what();
    }
    return "(taken)";
}

TEST(SiteLock, ASecondSessionIsRefusedWhileTheFirstHoldsIt) {
    const std::string path = lock_path("lock_same");
    {
        SiteLock lock(path);
        EXPECT_EQ(common::read_file(path, "lock"), std::to_string(getpid()) + "\n");
        const std::string error = refusal(path);
        EXPECT_NE(error.find("in use by pid " + std::to_string(getpid())), std::string::npos)
            << error;
        EXPECT_EQ(error.find('\n'), std::string::npos);
    }
    EXPECT_EQ(refusal(path), "(taken)");  // released by the destructor
}

TEST(SiteLock, AHolderKilledWithSigkillLeavesNoStaleLock) {
    const std::string path = lock_path("lock_kill");
    int ready[2];
    ASSERT_EQ(pipe(ready), 0);
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        close(ready[0]);
        SiteLock lock(path);
        if (write(ready[1], "x", 1) != 1) _exit(1);
        for (;;) pause();
    }
    close(ready[1]);
    char byte = 0;
    ASSERT_EQ(read(ready[0], &byte, 1), 1);
    close(ready[0]);
    const std::string error = refusal(path);
    EXPECT_NE(error.find("in use by pid " + std::to_string(child)), std::string::npos) << error;
    ASSERT_EQ(kill(child, SIGKILL), 0);
    int status = 0;
    ASSERT_EQ(waitpid(child, &status, 0), child);
    EXPECT_EQ(refusal(path), "(taken)");
}

}  // namespace
}  // namespace ltm::map
