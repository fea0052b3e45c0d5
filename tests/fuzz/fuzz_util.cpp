#include "fuzz_util.hpp"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;

namespace ltm::fuzz {
namespace {

struct Scratch {
    std::string dir;
    Scratch() {
        const char* tmp = std::getenv("TMPDIR");
        const fs::path base = fs::is_directory("/dev/shm") ? fs::path("/dev/shm")
                                                           : fs::path(tmp && *tmp ? tmp : "/tmp");
        dir = (base / ("ltm_fuzz_" + std::to_string(::getpid()))).string();
        fs::create_directories(dir);
    }
    ~Scratch() {
        std::error_code ec;
        fs::remove_all(dir, ec);
    }
};

}  // namespace

const std::string& scratch_dir() {
    static Scratch scratch;
    return scratch.dir;
}

std::string write_input(const std::uint8_t* data, std::size_t size, const std::string& name) {
    const std::string path = scratch_dir() + "/" + name;
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    if (!out.flush()) finding("cannot write the input to " + path);
    return path;
}

void clear_dir(const std::string& dir) {
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(dir, ec)) fs::remove_all(e.path(), ec);
}

void expect_one_line(const std::exception& e) {
    const std::string what = e.what();
    if (what.empty()) finding("an error with an empty message");
    if (what.find_first_of("\n\r") != std::string::npos)
        finding("an error of more than one line: " + what);
}

void finding(const std::string& what) {
    std::fprintf(stderr, "ltm fuzz finding: %s\n", what.c_str());
    std::abort();
}

}  // namespace ltm::fuzz
