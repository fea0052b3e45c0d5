#include "link/core/payload_codec.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

#include "common/core/cdr_cursor.hpp"
#include "link/core/local_map_columns.hpp"

using namespace ltm::link;

namespace {

const std::string kKeyframe = "ltm_msgs::msg::dds_::Keyframe_";
const std::string kLocalMap = "ltm_msgs::msg::dds_::LocalMap_";

// Messages laid out by hand after the IDL (XCDR1 little endian, as Cyclone writes them;
// payload_codec_messages_test checks the codec on Cyclone's own bytes).
struct Cdr {
    std::vector<std::uint8_t> bytes{0, 1, 0, 0};
    ltm::common::CdrWriter w{bytes};
    template <class T>
    void put(T v) {
        w.write(v);
    }
    void str(const std::string& s) {
        put(static_cast<std::uint32_t>(s.size() + 1));
        w.bytes(s.c_str(), s.size() + 1);
    }
    void header(const std::string& frame) {
        put(std::int32_t{1700000000});
        put(std::uint32_t{123456789});
        str(frame);
    }
    void pose(double x) {
        for (int i = 0; i < 7; ++i) put(x + i);
    }
    void floats(const std::vector<float>& v) {
        put(static_cast<std::uint32_t>(v.size()));
        for (float f : v) put(f);
    }
};

// A keyframe: `points` x y z intensity points of a scan around the sensor, two 20 x 60
// descriptors (Scan Context, ScanContext++).
std::vector<std::uint8_t> keyframe(int points, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> angle(0.0f, 6.2832f), range(2.0f, 60.0f), z(-2, 8);
    Cdr c;
    c.header("odom");
    c.put(std::uint64_t{42});
    c.put(std::uint64_t{420});
    c.put(std::uint64_t{3});
    c.put(std::uint32_t{1});  // segment
    c.pose(10.5);
    c.pose(0.25);
    c.header("lidar");
    c.put(std::uint32_t{1});
    c.put(static_cast<std::uint32_t>(points));
    c.put(std::uint32_t{4});
    const char* names[] = {"x", "y", "z", "intensity"};
    for (std::uint32_t i = 0; i < 4; ++i) {
        c.str(names[i]);
        c.put(4 * i);
        c.put(std::uint8_t{7});
        c.put(std::uint32_t{1});
    }
    c.put(std::uint8_t{0});
    c.put(std::uint32_t{16});
    c.put(static_cast<std::uint32_t>(16 * points));
    c.put(static_cast<std::uint32_t>(16 * points));  // data: sequence<uint8>
    for (int i = 0; i < points; ++i) {
        const float a = angle(rng), r = range(rng);
        const float p[4] = {r * std::cos(a), r * std::sin(a), z(rng), std::floor(r)};
        c.w.bytes(p, sizeof p);
    }
    c.put(std::uint8_t{1});             // is_dense
    for (std::uint8_t kind : {0, 1}) {  // kind, rings, sectors, max_range, values, spreads, ...
        c.put(kind);
        c.put(std::uint16_t{20});
        c.put(std::uint16_t{60});
        c.put(80.0f);
        std::vector<float> values(1200);
        for (std::size_t i = 0; i < values.size(); ++i)  // heights, 0 in empty bins
            values[i] = i % 3 == 0 ? 0.0f : z(rng);
        c.floats(values);
        std::vector<float> spreads;
        for (int i = 0; kind == 1 && i < 1200; ++i) spreads.push_back(std::abs(z(rng)) / 8);
        c.floats(spreads);
        c.put(std::uint32_t{1200});  // occupied: every third bin empty
        for (int i = 0; i < 1200; ++i) c.put(std::uint8_t(i % 3 != 0));
        c.put(0.0f);   // min_range
        c.put(1.73f);  // sensor_height
    }
    return c.bytes;
}

// A local map of `voxels` voxels on a 0.5 m lattice, some with `seen` indices.
std::vector<std::uint8_t> local_map(int voxels, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> cell(-80, 80), seen(0, 3);
    std::uniform_real_distribution<float> unit(0, 1);
    Cdr c;
    c.header("odom");
    c.put(std::uint64_t{7});
    c.put(std::uint32_t{2});
    c.put(std::uint8_t{1});
    c.put(std::uint32_t{0});
    c.pose(1.0);
    c.pose(2.0);
    for (int i = 0; i < 6; ++i) c.put(-40.0 + i);
    c.put(0.5f);
    c.put(std::uint32_t{3});
    for (double t : {100.0, 100.1, 100.2}) c.put(t);
    c.put(static_cast<std::uint32_t>(voxels));
    for (int v = 0; v < voxels; ++v) {
        const int ix = cell(rng), iy = cell(rng), iz = cell(rng) / 10;
        for (int i : {ix, iy, iz}) c.put(static_cast<std::int32_t>(i));
        for (int i : {ix, iy, iz}) c.put(0.5f * i + 0.25f * unit(rng));
        for (int i = 0; i < 3; ++i) c.put(unit(rng));
        c.put(static_cast<std::uint32_t>(1 + 30 * unit(rng)));
        c.put(unit(rng));
        c.put(unit(rng));
        c.put(100.0 + unit(rng));  // life: created, last_seen, observations, health, seen
        c.put(100.2);
        c.put(std::uint32_t{3});
        c.put(0.9f);
        const int n = seen(rng);
        c.put(static_cast<std::uint32_t>(n));
        for (int i = 0; i < n; ++i) c.put(static_cast<std::uint16_t>(i));
    }
    return c.bytes;
}

std::string decode_error(const std::string& type, const std::vector<std::uint8_t>& wire) {
    try {
        decode_payload(type, wire);
    } catch (const std::runtime_error& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(PayloadCodec, KeyframesAreShuffledAndComeBackByteForByte) {
    const std::vector<std::uint8_t> cdr = keyframe(3000, 1);
    const std::vector<std::uint8_t> wire = encode_payload(kKeyframe, cdr);
    EXPECT_EQ(payload_codec(wire), PayloadCodec::kShuffled);
    EXPECT_EQ(decode_payload(kKeyframe, wire), cdr);
    // The shuffle is what makes it smaller than zstd alone (same level).
    const std::vector<std::uint8_t> plain = encode_payload("some::Other_", cdr);
    EXPECT_EQ(payload_codec(plain), PayloadCodec::kZstd);
    EXPECT_EQ(decode_payload("some::Other_", plain), cdr);
    EXPECT_LT(wire.size(), plain.size());
}

TEST(PayloadCodec, LocalMapsAreColumnsAndComeBackByteForByte) {
    for (int voxels : {0, 1, 2, 500}) {
        const std::vector<std::uint8_t> cdr = local_map(voxels, 2);
        const std::vector<std::uint8_t> wire = encode_payload(kLocalMap, cdr);
        if (voxels >= 2) {
            EXPECT_EQ(payload_codec(wire), PayloadCodec::kLocalMap) << voxels;
        }
        EXPECT_EQ(decode_payload(kLocalMap, wire), cdr) << voxels;
        if (voxels == 500) {
            const auto plain = encode_payload("some::Other_", cdr);
            EXPECT_LT(wire.size(), plain.size());
        }
    }
    // Cyclone's encapsulation options count the padding appended to a multiple of 4.
    std::vector<std::uint8_t> padded = local_map(100, 2);
    padded[3] = 2;
    padded.insert(padded.end(), {0, 0});
    EXPECT_EQ(payload_codec(encode_payload(kLocalMap, padded)), PayloadCodec::kLocalMap);
    EXPECT_EQ(decode_payload(kLocalMap, encode_payload(kLocalMap, padded)), padded);
    // Columns: a rearrangement, the same bytes back.
    const std::vector<std::uint8_t> cdr = local_map(50, 3);
    const auto columns = local_map_to_columns(cdr);
    ASSERT_TRUE(columns);
    EXPECT_EQ(local_map_from_columns(*columns), cdr);
}

TEST(PayloadCodec, WhatDoesNotParseFallsBackToZstdOrIsStored) {
    std::vector<std::uint8_t> cdr = local_map(100, 4);
    cdr[cdr.size() / 2 + 1] ^= 0x40;  // a field changed: still a local map, still columns
    EXPECT_EQ(decode_payload(kLocalMap, encode_payload(kLocalMap, cdr)), cdr);
    // Any byte changed comes back; padding between voxel fields that is not zero would not come
    // back from columns, so those messages go as plain zstd.
    const std::vector<std::uint8_t> small = local_map(10, 5);
    int columns = 0, plain = 0;
    for (std::size_t i = 4; i < small.size(); ++i) {
        std::vector<std::uint8_t> changed = small;
        changed[i] ^= 0x5a;
        const std::vector<std::uint8_t> wire = encode_payload(kLocalMap, changed);
        ASSERT_EQ(decode_payload(kLocalMap, wire), changed) << i;
        (payload_codec(wire) == PayloadCodec::kLocalMap ? columns : plain)++;
    }
    EXPECT_GT(plain, 0);
    EXPECT_GT(columns, plain);
    // Cut short, not CDR at all, empty: zstd or stored, lossless.
    const std::vector<std::uint8_t> cut(cdr.begin(), cdr.begin() + cdr.size() / 3);
    EXPECT_EQ(decode_payload(kLocalMap, encode_payload(kLocalMap, cut)), cut);
    const std::vector<std::uint8_t> kf = keyframe(100, 6);
    const std::vector<std::uint8_t> kf_cut(kf.begin(), kf.begin() + 200);
    EXPECT_EQ(decode_payload(kKeyframe, encode_payload(kKeyframe, kf_cut)), kf_cut);
    for (const std::vector<std::uint8_t>& tiny :
         {std::vector<std::uint8_t>{}, std::vector<std::uint8_t>{0, 1, 0, 0, 9}}) {
        const std::vector<std::uint8_t> wire = encode_payload(kKeyframe, tiny);
        EXPECT_EQ(payload_codec(wire), PayloadCodec::kStored);
        EXPECT_EQ(decode_payload(kKeyframe, wire), tiny);
    }
    std::mt19937 rng(7);
    std::vector<std::uint8_t> noise(5000);
    for (auto& b : noise) b = static_cast<std::uint8_t>(rng());
    EXPECT_EQ(payload_codec(encode_payload(kLocalMap, noise)), PayloadCodec::kStored);
}

TEST(PayloadCodec, LevelsAndErrorsAreOneLine) {
    const std::vector<std::uint8_t> cdr = keyframe(500, 8);
    EXPECT_EQ(decode_payload(kKeyframe, encode_payload(kKeyframe, cdr, {19})), cdr);
    EXPECT_THROW(encode_payload(kKeyframe, cdr, {0}), std::runtime_error);
    EXPECT_EQ(decode_error(kKeyframe, {}), "payload: empty");
    EXPECT_EQ(decode_error(kKeyframe, {9, 0, 0}), "payload: unknown codec 9 (a newer robot?)");
    EXPECT_EQ(decode_error(kKeyframe, {1, 0, 0}), "payload: cut short in its header (3 B)");
    EXPECT_EQ(decode_error(kKeyframe, {0, 3, 0, 0, 0, 1, 2}),
              "payload: stored message of 2 B, the header says 3");
    const std::vector<std::uint8_t> map_wire = encode_payload(kLocalMap, local_map(100, 9));
    EXPECT_EQ(decode_error(kKeyframe, map_wire),
              "payload: local map columns given as ltm_msgs::msg::dds_::Keyframe_");
    std::vector<std::uint8_t> wire = encode_payload(kKeyframe, cdr);
    wire.push_back(0);
    EXPECT_EQ(decode_error(kKeyframe, wire), "payload: 1 bytes after the zstd frame");
}

// Every cut and many bit flips of valid wire forms: the CDR back or one line, never a crash
// (and, under the sanitizers, no invalid access).
TEST(PayloadCodec, DamagedWireFormsAreOneLineNeverACrash) {
    std::mt19937 rng(11);
    const std::pair<std::string, std::vector<std::uint8_t>> messages[] = {
        {kKeyframe, keyframe(200, 12)},
        {kLocalMap, local_map(60, 13)},
        {"some::Other_", keyframe(50, 14)},
        {kKeyframe, {0, 1, 0, 0, 1, 2, 3}}};
    int errors = 0, decoded = 0;
    for (const auto& message : messages) {
        const std::string& type = message.first;
        const std::vector<std::uint8_t> wire = encode_payload(type, message.second);
        const auto check = [&](const std::vector<std::uint8_t>& damaged) {
            try {
                decode_payload(type, damaged);
                ++decoded;  // a flip in a shuffled range's stride, say, decodes to other bytes
            } catch (const std::runtime_error& e) {
                ++errors;
                const std::string what = e.what();
                EXPECT_EQ(what.rfind("payload: ", 0) == 0 || what.rfind("local map", 0) == 0, true)
                    << what;
                EXPECT_EQ(what.find('\n'), std::string::npos) << what;
            }
        };
        for (std::size_t n = 0; n < wire.size(); ++n)
            check(std::vector<std::uint8_t>(wire.begin(), wire.begin() + n));
        for (int i = 0; i < 3000; ++i) {
            std::vector<std::uint8_t> damaged = wire;
            const int flips = 1 + static_cast<int>(rng() % 3);
            for (int f = 0; f < flips; ++f) damaged[rng() % damaged.size()] ^= 1u << (rng() % 8);
            check(damaged);
        }
    }
    EXPECT_GT(errors, 0);
    EXPECT_GT(decoded + errors, 4 * 3000);
}
