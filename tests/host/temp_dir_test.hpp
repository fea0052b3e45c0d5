#pragma once
// A GoogleTest fixture with a fresh temporary folder per test (named after the test and the
// process), removed after a passing test and kept after a failing one for a look.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace ltm::tests {

class TempDirTest : public ::testing::Test {
  protected:
    explicit TempDirTest(std::string prefix) : prefix_(std::move(prefix)) {}
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = std::filesystem::temp_directory_path() /
               (prefix_ + std::string(info->name()) + "_" + std::to_string(::getpid()));
        std::filesystem::remove_all(dir_);
        std::filesystem::create_directories(dir_);
    }
    void TearDown() override {
        if (!HasFailure()) std::filesystem::remove_all(dir_);
    }
    // Writes `text` to a file of the folder; returns its path.
    std::string write(const std::string& name, const std::string& text) {
        const std::string file = path(name);
        std::ofstream(file) << text;
        return file;
    }
    std::string path(const std::string& name) const { return (dir_ / name).string(); }

    std::filesystem::path dir_;

  private:
    std::string prefix_;
};

}  // namespace ltm::tests
