#include "map/core/map_manifest.hpp"

#include <gtest/gtest.h>

namespace ltm::map {
namespace {

places::ScanContextConfig default_localisation_descriptor_for_test() {
    places::ScanContextConfig c;
    c.kind = places::ScanContextKind::kMeanVariance;
    c.rings = 20;
    c.sectors = 60;
    return c;
}

Manifest sample() {
    Manifest m;
    m.revision = 12;
    m.descriptor.kind = places::ScanContextKind::kMeanVariance;
    m.descriptor.rings = 10;
    m.descriptor.sectors = 24;
    m.descriptor.sensor_height = 1.73;
    ManifestEntry g;
    g.kind = "graph";
    g.file = "graph_00000000000000ff.bin";
    g.size = 1567;
    g.hash = 0xff;
    ManifestEntry k;
    k.kind = "keyframes";
    k.file = "keyframes_00000000_0123456789abcdef.bin";
    k.size = 2359;
    k.hash = 0x0123456789abcdefull;
    k.first = 0;
    k.count = 2;
    ManifestEntry l;
    l.kind = "local_map";
    l.node = 20;
    l.file = "local_maps/lm_00000020_fedcba9876543210.bin";
    l.size = 17353;
    l.hash = 0xfedcba9876543210ull;
    m.files = {g, k, l};
    return m;
}

// The what() of parsing `text`; "" when it parses.
std::string error_of(const std::string& text) {
    try {
        parse_manifest(text);
    } catch (const MapFormatError& e) {
        return e.what();
    }
    return "";
}

TEST(MapManifest, WrittenAndParsedByOneDescription) {
    const std::string text = write_manifest(sample());
    EXPECT_EQ(text,
              "ltm_map 1\n"
              "revision 12\n"
              "descriptor 1 10 24 80 0 1.73\n"
              "graph graph_00000000000000ff.bin 1567 00000000000000ff\n"
              "keyframes keyframes_00000000_0123456789abcdef.bin 2359 0123456789abcdef 0 2\n"
              "local_map 20 local_maps/lm_00000020_fedcba9876543210.bin 17353 fedcba9876543210\n"
              "end 3\n");
    const Manifest back = parse_manifest(text);
    EXPECT_EQ(write_manifest(back), text);
    EXPECT_EQ(back.files[2].node, 20u);
    EXPECT_EQ(back.files[1].hash, 0x0123456789abcdefull);
    EXPECT_EQ(back.descriptor.kind, places::ScanContextKind::kMeanVariance);
    // Format 1: no localisation descriptors.
    EXPECT_EQ(back.version, 1u);
    EXPECT_FALSE(has_localisation_descriptors(back.localisation_descriptor));
    EXPECT_EQ(back.localisation_descriptor.rings, 0);
    // Blank lines and extra spaces are allowed.
    std::string spaced = text;
    spaced.insert(spaced.find("revision"), "\n  \n");
    spaced.insert(spaced.find("12"), "   ");
    EXPECT_EQ(write_manifest(parse_manifest(spaced)), text);
}

TEST(MapManifest, Format2AddsTheLocalisationDescriptorLine) {
    Manifest m = sample();
    m.localisation_descriptor.kind = places::ScanContextKind::kMeanVariance;
    m.localisation_descriptor.rings = 20;
    m.localisation_descriptor.sectors = 60;
    m.localisation_descriptor.max_range = 40;
    m.localisation_descriptor.min_range = 0.5;
    m.localisation_descriptor.sensor_height = 1;
    const std::string text = write_manifest(m);
    EXPECT_EQ(text.substr(0, text.find("graph")),
              "ltm_map 2\n"
              "revision 12\n"
              "descriptor 1 10 24 80 0 1.73\n"
              "localisation_descriptor 1 20 60 40 0.5 1\n");
    const Manifest back = parse_manifest(text);
    EXPECT_EQ(back.version, 2u);
    const places::ScanContextConfig& l = back.localisation_descriptor;
    EXPECT_EQ(l.kind, places::ScanContextKind::kMeanVariance);
    EXPECT_EQ(l.rings, 20);
    EXPECT_EQ(l.sectors, 60);
    EXPECT_EQ(l.max_range, 40.0);
    EXPECT_EQ(l.min_range, 0.5);
    EXPECT_EQ(l.sensor_height, 1.0);
    EXPECT_EQ(write_manifest(back), text);
    auto replaced = [&](const std::string& from, const std::string& to) {
        std::string t = text;
        t.replace(t.find(from), from.size(), to);
        return t;
    };
    // Format 2 without the line, with a broken one, or format 1 with it.
    EXPECT_EQ(error_of(replaced("localisation_descriptor 1 20 60 40 0.5 1\n", "")),
              "manifest.txt: line 4 at byte 51: 'graph' out of place (expected "
              "'localisation_descriptor <kind 0|1> <rings> <sectors> <max_range> <min_range> "
              "<sensor_height>')");
    EXPECT_EQ(error_of(replaced("localisation_descriptor 1 20", "localisation_descriptor 1 0")),
              "manifest.txt: line 4 at byte 51: localisation_descriptor.rings: must be in [1, "
              "1000] (got 0)");
    EXPECT_EQ(error_of(replaced("localisation_descriptor 1", "localisation_descriptor 2")),
              "manifest.txt: line 4 at byte 51: localisation_descriptor kind must be 0 or 1");
    EXPECT_EQ(error_of(replaced("ltm_map 2", "ltm_map 1")),
              "manifest.txt: line 4 at byte 51: 'localisation_descriptor' out of place");
}

TEST(MapManifest, Format3ListsTheSessionsThatBuiltTheMap) {
    Manifest m = sample();
    m.localisation_descriptor = default_localisation_descriptor_for_test();
    m.sessions = {{0, 12.5, 1180.25, 53, 0}, {2, 86400.0, 87000.5, 1, 40}};
    const std::string text = write_manifest(m);
    EXPECT_NE(text.find("ltm_map 4\n"), std::string::npos) << text;
    EXPECT_NE(text.find("\nsession 0 12.5 1180.25 53 0\nsession 2 86400 87000.5 1 40\ngraph "),
              std::string::npos)
        << text;
    const Manifest back = parse_manifest(text);
    EXPECT_EQ(back.version, 4u);
    ASSERT_EQ(back.sessions.size(), 2u);
    EXPECT_EQ(back.sessions[1].id, 2u);
    EXPECT_EQ(back.sessions[1].first_stamp, 86400.0);
    EXPECT_EQ(back.sessions[1].last_stamp, 87000.5);
    EXPECT_EQ(back.sessions[1].local_maps_added, 1u);
    EXPECT_EQ(back.sessions[1].local_maps_updated, 40u);
    EXPECT_EQ(write_manifest(back), text);
    auto replaced = [&](const std::string& from, const std::string& to) {
        std::string t = text;
        t.replace(t.find(from), from.size(), to);
        return t;
    };
    // Sessions out of order, stamps backwards, a session line in format 2.
    EXPECT_EQ(error_of(replaced("session 2 ", "session 0 ")),
              "manifest.txt: line 6 at byte 118: session 0 after session 0 (ids ascending)");
    EXPECT_EQ(error_of(replaced("86400 87000.5", "87001 87000.5")),
              "manifest.txt: line 6 at byte 118: session stamps must be finite, the first not "
              "after the last");
    // A format-3 manifest (the same lines; its files are rows, not compressed) still reads.
    EXPECT_EQ(parse_manifest(replaced("ltm_map 4", "ltm_map 3")).version, 3u);
    EXPECT_EQ(error_of(replaced("ltm_map 4", "ltm_map 2")),
              "manifest.txt: line 5 at byte 90: 'session' out of place");
    // Without sessions the map stays in format 2.
    m.sessions.clear();
    EXPECT_EQ(write_manifest(m).rfind("ltm_map 2\n", 0), 0u);
}

TEST(MapManifest, DamageIsNamedByLineAndOffset) {
    const std::string text = write_manifest(sample());
    auto replaced = [&](const std::string& from, const std::string& to) {
        std::string t = text;
        t.replace(t.find(from), from.size(), to);
        return t;
    };
    EXPECT_EQ(
        error_of(replaced("revision", "revisoin")),
        "manifest.txt: line 2 at byte 10: unknown entry 'revisoin' (expected 'revision <n>')");
    EXPECT_EQ(error_of(replaced("revision 12", "end 3")),
              "manifest.txt: line 2 at byte 10: 'end' out of place (expected 'revision <n>')");
    EXPECT_EQ(error_of(replaced("ltm_map 1", "ltm_map 5")),
              "manifest.txt: line 1 at byte 0: format version 5 is not supported (this build "
              "reads versions 1 to 4)");
    EXPECT_EQ(error_of(replaced("ltm_map 1", "ltm_map 0")),
              "manifest.txt: line 1 at byte 0: format version 0 is not supported (this build "
              "reads versions 1 to 4)");
    EXPECT_EQ(error_of(replaced(" 1567 ", " 15x7 ")),
              "manifest.txt: line 4 at byte 51: expected 'graph <file> <size> <hash>'");
    EXPECT_EQ(error_of(replaced("00000000000000ff\n", "00000000000000FF\n")),
              "manifest.txt: line 4 at byte 51: expected 'graph <file> <size> <hash>'");
    EXPECT_EQ(error_of(replaced("2359 0123456789abcdef 0 2", "2359 0123456789abcdef 0 2 9")),
              "manifest.txt: line 5 at byte 106: unexpected '9' at the end of the line");
    EXPECT_EQ(error_of(replaced("local_maps/lm", "../lm")),
              "manifest.txt: line 6 at byte 182: file name '../lm_00000020_fedcba9876543210.bin' "
              "is not a plain relative path");
    EXPECT_EQ(error_of(replaced("end 3", "end 4")),
              "manifest.txt: line 7 at byte 262: 'end' counts 4 entries, the manifest has 3");
    EXPECT_EQ(error_of(replaced("descriptor 1 10", "descriptor 1 0")),
              "manifest.txt: line 3 at byte 22: descriptor.rings: must be in [1, 1000] (got 0)");
    EXPECT_EQ(error_of(text + "end 3\n"), "manifest.txt: line 8 at byte 268: text after 'end'");
    EXPECT_EQ(error_of(replaced("keyframes keyframes_00000000_0123456789abcdef.bin 2359 "
                                "0123456789abcdef 0 2",
                                "graph keyframes_00000000_0123456789abcdef.bin 2359 "
                                "0123456789abcdef")),
              "manifest.txt: line 5 at byte 106: a second graph entry");
    EXPECT_EQ(error_of(text.substr(0, text.find("local_map"))),
              "manifest.txt: truncated: no 'end' line (an interrupted write?)");
    EXPECT_EQ(error_of(text.substr(0, text.find("keyframes") - 20)),
              "manifest.txt: line 4 at byte 51: expected 'graph <file> <size> <hash>'");
    EXPECT_EQ(error_of(""), "manifest.txt: empty: not an ltm map manifest");
    EXPECT_EQ(error_of("ltm_map 1\nrevision 1\ndescriptor 0 20 60 80 0 2\nend 0\n"),
              "manifest.txt: no 'graph' entry");
}

}  // namespace
}  // namespace ltm::map
