#include "common/core/streamed_file.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "common/core/byte_io.hpp"
#include "common/core/io_error.hpp"

namespace ltm::common {
namespace {

namespace fs = std::filesystem;

std::string temp_file(const std::string& name) {
    return (fs::temp_directory_path() / ("ltm_streamed_" + std::to_string(::getpid()) + "_" + name))
        .string();
}

std::vector<std::uint8_t> section_of(std::uint32_t value) {
    ByteWriter w;
    w.section("s", [&](auto& s) { s.value(value); });
    return w.bytes();
}

TEST(StreamedFile, WrittenInPiecesCommittedWholeReadBackBySection) {
    const std::string path = temp_file("whole.bin");
    {
        AtomicFileWriter out(path);
        for (std::uint32_t v : {7u, 8u, 9u}) out.append(section_of(v));
        EXPECT_FALSE(fs::exists(path));  // not before commit
        out.commit();
    }
    EXPECT_TRUE(fs::exists(path));
    EXPECT_FALSE(fs::exists(path + ".tmp"));
    SectionFileReader in(path, "whole.bin");
    for (std::uint32_t v : {7u, 8u, 9u}) {
        in.next_section("s");
        ByteReader r = in.reader();
        r.section("s", [&](ByteReader& s) { EXPECT_EQ(s.get<std::uint32_t>("v"), v); });
    }
    EXPECT_TRUE(in.at_end());
    fs::remove(path);
}

TEST(StreamedFile, AWriterNotCommittedLeavesTheOldFile) {
    const std::string path = temp_file("old.bin");
    { std::ofstream(path) << "old"; }
    {
        AtomicFileWriter out(path);
        out.append(section_of(1));
    }  // an error before commit: destroyed
    std::ifstream f(path);
    std::string text;
    f >> text;
    EXPECT_EQ(text, "old");
    EXPECT_FALSE(fs::exists(path + ".tmp"));
    fs::remove(path);
}

TEST(StreamedFile, ATruncatedOrDamagedSectionIsOneLine) {
    const std::string path = temp_file("cut.bin");
    std::vector<std::uint8_t> bytes = section_of(5);
    {
        std::ofstream f(path, std::ios::binary);
        f.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size() - 2));
    }
    SectionFileReader cut(path, "cut.bin");
    try {
        cut.next_section("s");
        FAIL() << "a truncated section was read";
    } catch (const FormatError& e) {
        EXPECT_NE(std::string(e.what()).find("cut.bin"), std::string::npos) << e.what();
    }
    bytes[5] ^= 0x40;  // the body: the CRC no longer matches
    {
        std::ofstream f(path, std::ios::binary | std::ios::trunc);
        f.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    }
    SectionFileReader damaged(path, "cut.bin");
    damaged.next_section("s");
    ByteReader r = damaged.reader();
    EXPECT_THROW(r.section("s", [](ByteReader& s) { s.get<std::uint32_t>("v"); }), FormatError);
    fs::remove(path);
    EXPECT_THROW(SectionFileReader(path, "gone.bin"), IoError);
}

}  // namespace
}  // namespace ltm::common
