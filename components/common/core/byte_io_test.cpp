#include "common/core/byte_io.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "common/core/crc32.hpp"

namespace ltm::common {
namespace {

struct Sample {
    std::uint16_t id = 0;
    double stamp = 0.0;
    std::string name;
    std::vector<std::int32_t> values;
};

// One description for both directions.
template <class IO, class S>
void sample(IO& io, S& s) {
    io.item("sample");
    io.value(s.id, "id");
    io.value(s.stamp, "stamp");
    io.str(s.name, "name");
    std::uint32_t n = static_cast<std::uint32_t>(s.values.size());
    io.value(n, "count");
    if constexpr (IO::kReading) {
        io.check(n <= io.remaining() / 4, "count", io.offset() - 4, "more values than bytes");
        s.values.resize(n);
    }
    for (std::uint32_t i = 0; i < n; ++i) {
        io.item("values", i);
        io.value(s.values[i]);
    }
}

std::vector<std::uint8_t> encode(const Sample& s) {
    ByteWriter w;
    sample(w, s);
    return w.bytes();
}

Sample decode(const std::vector<std::uint8_t>& b) {
    ByteReader r("sample.bin", b.data(), b.size());
    Sample s;
    sample(r, s);
    r.expect_end("end");
    return s;
}

// The error of reading `bytes`; fails the test when there is none.
FormatError error_of(const std::vector<std::uint8_t>& bytes) {
    try {
        decode(bytes);
    } catch (const FormatError& e) {
        return e;
    }
    ADD_FAILURE() << "no error";
    return FormatError("", "");
}

TEST(ByteIo, LittleEndianLayout) {
    ByteWriter w;
    w.value(std::uint32_t(0x01020304));
    w.value(std::int16_t(-2));
    w.str("ab");
    const std::vector<std::uint8_t> expected = {4, 3, 2, 1, 0xfe, 0xff, 2, 0, 0, 0, 'a', 'b'};
    EXPECT_EQ(w.bytes(), expected);
}

TEST(ByteIo, OneDescriptionWritesAndReads) {
    Sample s;
    s.id = 513;
    s.stamp = -12.25;
    s.name = "scan";
    s.values = {1, -7, 1 << 30};
    const std::vector<std::uint8_t> bytes = encode(s);
    EXPECT_EQ(bytes.size(), 2u + 8u + 4u + 4u + 4u + 12u);
    const Sample back = decode(bytes);
    EXPECT_EQ(back.id, s.id);
    EXPECT_EQ(back.stamp, s.stamp);
    EXPECT_EQ(back.name, s.name);
    EXPECT_EQ(back.values, s.values);
}

TEST(ByteIo, TruncatedInputNamesTheFieldAndOffset) {
    Sample s;
    s.name = "scan";
    s.values = {1, 2, 3};
    const std::vector<std::uint8_t> bytes = encode(s);
    // Cut inside values[1]: the count (3) no longer fits in the bytes left.
    const FormatError e = error_of(std::vector<std::uint8_t>(bytes.begin(), bytes.begin() + 28));
    EXPECT_EQ(e.file(), "sample.bin");
    EXPECT_EQ(e.field(), "sample.count");
    EXPECT_EQ(e.offset(), 18u);
    EXPECT_STREQ(e.what(), "sample.bin: sample.count at byte 18: more values than bytes");
    // Every shorter prefix fails with one line naming an offset within the input.
    for (std::size_t n = 0; n < bytes.size(); ++n) {
        const FormatError f = error_of(std::vector<std::uint8_t>(bytes.begin(), bytes.begin() + n));
        EXPECT_LE(f.offset(), n) << n;
        EXPECT_EQ(std::string(f.what()).find('\n'), std::string::npos) << n;
        EXPECT_EQ(std::string(f.what()).rfind("sample.bin: ", 0), 0u) << f.what();
    }
    // Cut inside the string: the length says 4, 2 bytes are there.
    const FormatError g = error_of(std::vector<std::uint8_t>(bytes.begin(), bytes.begin() + 16));
    EXPECT_STREQ(g.what(), "sample.bin: sample.name at byte 14: truncated: needs 4 bytes, 2 left");
}

TEST(ByteIo, ItemsNameTheElement) {
    std::vector<std::uint8_t> bytes(12, 0);
    ByteReader r("x", bytes.data(), bytes.size(), 100);
    r.item("voxels", 17);
    r.get<std::uint64_t>("normal");
    try {
        r.get<std::uint64_t>("normal");
        FAIL();
    } catch (const FormatError& e) {
        EXPECT_EQ(e.field(), "voxels[17].normal");
        EXPECT_EQ(e.offset(), 108u);  // offsets count from the base
        EXPECT_STREQ(e.what(),
                     "x: voxels[17].normal at byte 108: truncated: needs 8 bytes, 4 left");
    }
}

TEST(ByteIo, NonFiniteNumbersAreDamage) {
    ByteWriter w;
    w.value(1.5f);
    w.value(std::numeric_limits<double>::quiet_NaN());
    w.value(std::numeric_limits<float>::infinity());
    ByteReader r("f", w.bytes().data(), w.bytes().size());
    EXPECT_EQ(r.get<float>("a"), 1.5f);
    try {
        r.get<double>("b");
        FAIL();
    } catch (const FormatError& e) {
        EXPECT_STREQ(e.what(), "f: b at byte 4: not a finite number");
    }
}

TEST(ByteIo, SectionsCheckTheirLengthAndCrc) {
    ByteWriter w;
    w.value(std::uint8_t(9));
    w.section("body", [](ByteWriter& s) {
        s.value(std::uint32_t(7));
        s.str("payload");
    });
    std::vector<std::uint8_t> bytes = w.bytes();
    ASSERT_EQ(bytes.size(), 1u + 4u + 15u + 4u);
    std::uint32_t stored = 0;
    std::memcpy(&stored, bytes.data() + 20, 4);
    EXPECT_EQ(stored, crc32(bytes.data() + 5, 15));

    auto read = [](const std::vector<std::uint8_t>& b) {
        ByteReader r("s.bin", b.data(), b.size());
        r.get<std::uint8_t>("tag");
        std::string text;
        r.section("body", [&](ByteReader& s) {
            EXPECT_EQ(s.offset(), 5u);
            s.get<std::uint32_t>("n");
            s.str(text, "text");
        });
        r.expect_end("end");
        return text;
    };
    EXPECT_EQ(read(bytes), "payload");

    std::vector<std::uint8_t> flipped = bytes;
    flipped[10] ^= 0x20;
    try {
        read(flipped);
        FAIL();
    } catch (const FormatError& e) {
        EXPECT_EQ(e.field(), "body");
        EXPECT_EQ(e.offset(), 5u);
        EXPECT_NE(std::string(e.what()).find("checksum mismatch over bytes 5-20"),
                  std::string::npos)
            << e.what();
    }
    std::vector<std::uint8_t> cut(bytes.begin(), bytes.end() - 3);
    try {
        read(cut);
        FAIL();
    } catch (const FormatError& e) {
        EXPECT_STREQ(e.what(),
                     "s.bin: body at byte 1: section of 15 bytes does not fit in the 16 bytes "
                     "left (truncated or damaged length)");
    }
    std::vector<std::uint8_t> longer = bytes;
    longer.push_back(0);
    try {
        read(longer);
        FAIL();
    } catch (const FormatError& e) {
        EXPECT_STREQ(e.what(), "s.bin: end at byte 24: 1 unexpected bytes after the end");
    }
}

TEST(ByteIo, BlocksAndLengthsPatchedLater) {
    ByteWriter w;
    const std::size_t at = w.begin_length<std::uint64_t>();
    w.str("k");
    w.str("v");
    w.end_length<std::uint64_t>(at);
    ByteReader r("m", w.bytes().data(), w.bytes().size());
    EXPECT_EQ(r.get<std::uint64_t>("length"), 10u);
    std::vector<std::uint8_t> b32;
    ByteWriter v(b32);  // appends to a vector it is given
    const std::size_t at32 = v.begin_length<std::uint32_t>();
    v.value(std::uint16_t(3));
    v.end_length<std::uint32_t>(at32);
    ASSERT_EQ(b32.size(), 6u);
    ByteReader outer("m", b32.data(), b32.size());
    ByteReader inner = outer.block32("map");
    EXPECT_EQ(inner.remaining(), 2u);
    EXPECT_EQ(inner.offset(), 4u);
    EXPECT_EQ(inner.get<std::uint16_t>("key"), 3u);
    EXPECT_EQ(outer.remaining(), 0u);
}

}  // namespace
}  // namespace ltm::common
