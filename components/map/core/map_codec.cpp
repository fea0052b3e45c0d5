#include "map/core/map_codec.hpp"

// One file on purpose (575 lines): every section of every map file is described once by a
// template that both encodes and decodes it, and the sections share those field helpers; split
// apart, a layout change would have to be made in two places.

#include <algorithm>
#include <cmath>
#include <cstring>
#include <type_traits>
#include <unordered_set>

#include "common/core/byte_io.hpp"
#include "common/core/column_block.hpp"
#include "map/core/local_map_columns.hpp"
#include "map/core/map_format.hpp"

namespace ltm::map {
namespace {

using common::ByteReader;
using common::ByteWriter;

constexpr char kLocalMapMagic[8] = {'L', 'T', 'M', '-', 'L', 'M', 'A', 'P'};
constexpr char kGraphMagic[8] = {'L', 'T', 'M', '-', 'G', 'R', 'P', 'H'};
constexpr char kKeyframesMagic[8] = {'L', 'T', 'M', '-', 'K', 'F', 'R', 'M'};
constexpr std::size_t kChunk = 4096;  // items a section

// Each record below is described once, for both directions: ByteWriter runs it over a const
// record and writes, ByteReader runs it over a fresh record, reads and checks. The checks are
// no-ops when writing; what only reading does (allocating, the checks that need more than one
// field) is under `if constexpr (IO::kReading)`.

std::string range_name(const char* what, std::size_t a, std::size_t b) {
    return std::string(what) + "[" + std::to_string(a) + ".." + std::to_string(b) + "]";
}

std::string as_string(const ByteWriter& w) {
    return std::string(w.bytes().begin(), w.bytes().end());
}

// A value stored as `Stored` (a count or setting held as int in memory, as uint32 in the file).
template <class Stored, class IO, class T>
void value_as(IO& io, T& v, const char* field) {
    Stored s = static_cast<Stored>(v);
    io.value(s, field);
    if constexpr (IO::kReading) v = static_cast<T>(s);
}

// A bool as a uint8 0 or 1.
template <class IO, class B>
void flag(IO& io, B& b, const char* field) {
    const std::uint64_t at = io.offset();
    std::uint8_t v = b ? 1 : 0;
    io.value(v, field);
    io.check(v <= 1, field, at, "must be 0 or 1");
    if constexpr (IO::kReading) b = v == 1;
}

// An enumeration as a uint8 in [0, max].
template <class IO, class E>
void kind(IO& io, E& e, unsigned max, const char* field) {
    const std::uint64_t at = io.offset();
    std::uint8_t v = static_cast<std::uint8_t>(e);
    io.value(v, field);
    io.check(v <= max, field, at, [&] { return "unknown kind " + std::to_string(v); });
    if constexpr (IO::kReading) e = static_cast<E>(v);
}

template <class IO, class V>
void vec3(IO& io, V& v, const char* field) {
    for (int i = 0; i < 3; ++i) io.value(v[i], field);
}

// A rigid transform: 12 doubles, the 3x4 matrix row-major; when read, a rotation (det +1).
template <class IO, class T>
void pose(IO& io, T& pose, const char* field) {
    const std::uint64_t at = io.offset();
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 4; ++c) io.value(pose.matrix()(r, c), field);
    }
    if constexpr (IO::kReading) {
        const Eigen::Matrix3d R = pose.linear();
        io.check((R.transpose() * R - Eigen::Matrix3d::Identity()).norm() <= 1e-5 &&
                     R.determinant() >= 0.0,
                 field, at, "rotation is not orthonormal");
    }
}

// Float rounding: |n_old . n_new| of two unit normals may come out a hair above 1.
template <class IO, class F>
void unit_interval(IO& io, F& v, const char* field) {
    const std::uint64_t at = io.offset();
    io.value(v, field);
    io.check(v >= -1e-3f && v <= 1.001f, field, at,
             [&] { return "must be in [0, 1] (got " + std::to_string(v) + ")"; });
}

// The magic of the file's kind and the format version (1 or 2: reading, *version receives it).
template <class IO, class V>
void file_start(IO& io, const char (&magic)[8], const char* what, V& version) {
    char m[8];
    std::memcpy(m, magic, 8);
    io.raw(m, 8, "magic");
    io.check(std::memcmp(m, magic, 8) == 0, "magic", 0,
             [&] { return std::string("not an ltm ") + what + " file"; });
    const std::uint64_t at = io.offset();
    std::uint32_t v = version;
    io.value(v, "format version");
    io.check(readable_map_format(v), "format version", at,
             [&] { return unreadable_map_format(v); });
    if constexpr (IO::kReading) version = v;
}

// ---------------------------------------------------------------------------------------------
// Local maps.

template <class IO, class V>
void voxel(IO& io, V& v, float voxel_size, std::uint32_t n_times) {
    vec3(io, v.index, "index");
    const std::uint64_t at_centre = io.offset();
    vec3(io, v.centre, "centre");
    if constexpr (IO::kReading) {
        const float g = voxel_size;
        const Eigen::Vector3f lo = v.index.template cast<float>() * g;
        const float tol = std::max(1e-3f * g, 1e-6f * v.centre.cwiseAbs().maxCoeff());
        io.check(!((v.centre - lo).array() < -tol).any() &&
                     !((lo.array() + g - v.centre.array()) < -tol).any(),
                 "centre", at_centre, "outside the voxel's cell");
    }
    const std::uint64_t at_normal = io.offset();
    vec3(io, v.normal, "normal");
    if constexpr (IO::kReading) {
        const float nn = v.normal.norm();
        io.check(nn == 0.0f || std::abs(nn - 1.0f) <= 1e-3f, "normal", at_normal,
                 "neither zero nor a unit vector");
    }
    io.value(v.point_count, "point_count");
    unit_interval(io, v.planarity, "planarity");
    unit_interval(io, v.stability, "stability");
    io.value(v.life.created, "life.created");
    const std::uint64_t at_last = io.offset();
    io.value(v.life.last_seen, "life.last_seen");
    io.check(v.life.last_seen >= v.life.created, "life.last_seen", at_last, "before life.created");
    io.value(v.life.observations, "life.observations");
    unit_interval(io, v.life.health, "life.health");
    // At most 65535 indices are stored.
    std::uint16_t n_seen =
        static_cast<std::uint16_t>(std::min<std::size_t>(v.life.seen.size(), 65535));
    io.value(n_seen, "life.seen count");
    if constexpr (IO::kReading) v.life.seen.resize(n_seen);
    for (std::uint16_t k = 0; k < n_seen; ++k) {
        const std::uint64_t at = io.offset();
        io.value(v.life.seen[k], "life.seen");
        io.check(v.life.seen[k] < n_times, "life.seen", at, [&] {
            return "index " + std::to_string(v.life.seen[k]) + " beyond the " +
                   std::to_string(n_times) + " observation times";
        });
    }
}

// m: StoredLocalMap (node, session), d: its LocalMapData.
template <class IO, class M, class D, class V>
void local_map_file(IO& io, M& m, D& d, V& version) {
    file_start(io, kLocalMapMagic, "local map", version);
    std::uint32_t n_times = static_cast<std::uint32_t>(d.observation_times.size());
    std::uint64_t n_voxels = d.voxels.size();
    io.section("header", [&](auto& h) {
        h.item("header");
        h.value(m.node, "node");
        h.value(m.session, "session");
        h.value(d.id, "id");
        h.value(d.revision, "revision");
        flag(h, d.finished, "finished");
        pose(h, d.T_odom_anchor, "T_odom_anchor");
        pose(h, d.T_anchor_grid, "T_anchor_grid");
        vec3(h, d.bbox_min, "bbox_min");
        const std::uint64_t at_max = h.offset();
        vec3(h, d.bbox_max, "bbox_max");
        h.check(!(d.bbox_max.array() < d.bbox_min.array()).any(), "bbox_max", at_max,
                "below bbox_min");
        const std::uint64_t at_size = h.offset();
        h.value(d.voxel_size, "voxel_size");
        h.check(d.voxel_size > 0.0f, "voxel_size", at_size, "must be > 0");
        const std::uint64_t at_times = h.offset();
        h.value(n_times, "observation_count");
        const std::uint64_t at_voxels = h.offset();
        h.value(n_voxels, "voxel_count");
        if constexpr (IO::kReading) {
            // Each time takes 8 bytes, each voxel at least 74: a count beyond the file is damage.
            h.check(n_times <= h.source_size() / 8, "observation_count", at_times, [&] {
                return std::to_string(n_times) + " observation times cannot fit in a file of " +
                       std::to_string(h.source_size()) + " bytes";
            });
            // Format 4: compressed, each voxel takes more than one byte in 16 (about 25 measured).
            const std::uint64_t max_voxels =
                version >= 4 ? h.source_size() * 16 : h.source_size() / 74;
            h.check(n_voxels <= max_voxels, "voxel_count", at_voxels, [&] {
                return std::to_string(n_voxels) + " voxels cannot fit in a file of " +
                       std::to_string(h.source_size()) + " bytes";
            });
            d.observation_times.resize(n_times);
            d.voxels.resize(static_cast<std::size_t>(n_voxels));
        }
    });
    io.section("observation_times", [&](auto& t) {
        for (std::uint32_t i = 0; i < n_times; ++i) {
            t.item("observation_times", i);
            t.value(d.observation_times[i]);
        }
    });
    if (version >= 4) {  // one section: the voxels as compressed columns
        io.section("voxels", [&](auto& s) {
            if constexpr (IO::kReading) {
                read_voxel_columns(s, d);
            } else {
                write_voxel_columns(s, d);
            }
        });
        io.expect_end("end of file");
        return;
    }
    for (std::size_t a = 0; a < n_voxels; a += kChunk) {
        const std::size_t b = std::min<std::size_t>(n_voxels, a + kChunk);
        io.section(range_name("voxels", a, b - 1), [&](auto& s) {
            for (std::size_t i = a; i < b; ++i) {
                s.item("voxels", i);
                voxel(s, d.voxels[i], d.voxel_size, n_times);
            }
        });
    }
    io.expect_end("end of file");
}

// ---------------------------------------------------------------------------------------------
// The graph.

// ids: reading, the node ids read so far (each once).
template <class IO, class N>
void node(IO& io, N& n, std::unordered_set<std::uint64_t>& ids) {
    const std::uint64_t at = io.offset();
    io.value(n.id, "id");
    if constexpr (IO::kReading) {
        io.check(ids.insert(n.id).second, "id", at,
                 [&] { return "node id " + std::to_string(n.id) + " repeated"; });
    }
    io.value(n.local_map_id, "local_map_id");
    io.value(n.session, "session");
    flag(io, n.fixed, "fixed");
    pose(io, n.T_odom_anchor, "T_odom_anchor");
    pose(io, n.T_world_anchor, "T_world_anchor");
}

// ids: reading, the graph's node ids.
template <class IO, class E>
void edge(IO& io, E& e, const std::unordered_set<std::uint64_t>& ids) {
    const std::uint64_t at_from = io.offset();
    io.value(e.from, "from");
    const std::uint64_t at_to = io.offset();
    io.value(e.to, "to");
    if constexpr (IO::kReading) {
        io.check(ids.count(e.from) > 0, "from", at_from,
                 [&] { return "no node " + std::to_string(e.from); });
        io.check(ids.count(e.to) > 0, "to", at_to,
                 [&] { return "no node " + std::to_string(e.to); });
        io.check(e.to != e.from, "to", at_to, "an edge from a node to itself");
    }
    kind(io, e.kind, 1, "kind");
    flag(io, e.active, "active");
    pose(io, e.T_from_to, "T_from_to");
    const std::uint64_t at_info = io.offset();
    for (int k = 0; k < 36; ++k) io.value(e.information.data()[k], "information");
    if constexpr (IO::kReading) {
        const Matrix6d& I = e.information;
        io.check((I - I.transpose()).cwiseAbs().maxCoeff() <=
                         1e-9 * std::max(1.0, I.cwiseAbs().maxCoeff()) &&
                     !(I.diagonal().array() < 0.0).any(),
                 "information", at_info, "not a symmetric information matrix");
    }
    io.value(e.query_keyframe, "query_keyframe");
    io.value(e.match_keyframe, "match_keyframe");
    io.value(e.error_translation, "error_translation");
    io.value(e.error_rotation, "error_rotation");
}

template <class IO, class R, class Nodes, class Edges, class V>
void graph_file(IO& io, R& revision, Nodes& nodes, Edges& edges, V& version) {
    file_start(io, kGraphMagic, "graph", version);
    std::uint64_t n_nodes = nodes.size(), n_edges = edges.size();
    io.section("header", [&](auto& h) {
        h.item("header");
        h.value(revision, "revision");
        const std::uint64_t at_nodes = h.offset();
        h.value(n_nodes, "node_count");
        const std::uint64_t at_edges = h.offset();
        h.value(n_edges, "edge_count");
        if constexpr (IO::kReading) {
            h.check(n_nodes <= h.source_size() / 200, "node_count", at_nodes,
                    "more nodes than the file can hold");
            h.check(n_edges <= h.source_size() / 400, "edge_count", at_edges,
                    "more edges than the file can hold");
            nodes.assign(static_cast<std::size_t>(n_nodes), PoseGraphNode());
            edges.assign(static_cast<std::size_t>(n_edges), PoseGraphEdge());
        }
    });
    std::unordered_set<std::uint64_t> ids;
    for (std::size_t a = 0; a < n_nodes; a += kChunk) {
        const std::size_t b = std::min<std::size_t>(n_nodes, a + kChunk);
        io.section(range_name("nodes", a, b - 1), [&](auto& s) {
            for (std::size_t i = a; i < b; ++i) {
                s.item("nodes", i);
                node(s, nodes[i], ids);
            }
        });
    }
    for (std::size_t a = 0; a < n_edges; a += kChunk) {
        const std::size_t b = std::min<std::size_t>(n_edges, a + kChunk);
        io.section(range_name("edges", a, b - 1), [&](auto& s) {
            for (std::size_t i = a; i < b; ++i) {
                s.item("edges", i);
                edge(s, edges[i], ids);
            }
        });
    }
    io.expect_end("end of file");
}

// ---------------------------------------------------------------------------------------------
// Keyframes.

template <class IO, class C>
void descriptor_config(IO& io, C& c) {
    const std::uint64_t at = io.offset();
    kind(io, c.kind, 1, "kind");
    value_as<std::uint32_t>(io, c.rings, "rings");
    value_as<std::uint32_t>(io, c.sectors, "sectors");
    io.value(c.max_range, "max_range");
    io.value(c.min_range, "min_range");
    io.value(c.sensor_height, "sensor_height");
    if constexpr (IO::kReading) {
        if (const auto problem = validate(c))
            io.fail_at(problem->key.c_str(), at, problem->problem);
    }
}

// The names of a descriptor's fields in errors.
struct DescriptorFields {
    const char *whole, *kind, *rings, *sectors, *value, *spread, *occupied;
};
constexpr DescriptorFields kLoopFields = {
    "descriptor",       "descriptor.kind",   "descriptor.rings",   "descriptor.sectors",
    "descriptor.value", "descriptor.spread", "descriptor.occupied"};
constexpr DescriptorFields kLocalisationFields = {
    "localisation_descriptor",         "localisation_descriptor.kind",
    "localisation_descriptor.rings",   "localisation_descriptor.sectors",
    "localisation_descriptor.value",   "localisation_descriptor.spread",
    "localisation_descriptor.occupied"};

// A keyframe's descriptor of the shape `cfg` (the file header's settings) or, when may_be_empty,
// an empty one (0 rings, 0 sectors, no bins).
template <class IO, class S>
void descriptor(IO& io, S& sc, const places::ScanContextConfig& cfg, const DescriptorFields& f,
                bool may_be_empty) {
    const std::uint64_t at_d = io.offset();
    kind(io, sc.kind, 1, f.kind);
    value_as<std::uint32_t>(io, sc.rings, f.rings);
    value_as<std::uint32_t>(io, sc.sectors, f.sectors);
    const bool mean_variance = sc.kind == places::ScanContextKind::kMeanVariance;
    if constexpr (IO::kReading) {
        const bool empty = may_be_empty && sc.rings == 0 && sc.sectors == 0;
        io.check(
            empty || (sc.kind == cfg.kind && sc.rings == cfg.rings && sc.sectors == cfg.sectors),
            f.whole, at_d, "shape differs from the file header's");
        const std::size_t bins = empty ? 0 : std::size_t(cfg.rings) * std::size_t(cfg.sectors);
        sc.value.resize(bins);
        if (mean_variance) sc.spread.resize(bins);
        sc.occupied.resize(bins);
    }
    for (std::size_t b = 0; b < sc.value.size(); ++b) {
        const std::uint64_t at = io.offset();
        io.value(sc.value[b], f.value);
        io.check(mean_variance || sc.value[b] >= 0.0f, f.value, at, "negative height");
    }
    if (mean_variance) {
        for (std::size_t b = 0; b < sc.spread.size(); ++b) {
            const std::uint64_t at = io.offset();
            io.value(sc.spread[b], f.spread);
            io.check(sc.spread[b] >= 0.0f, f.spread, at, "negative");
        }
    }
    for (std::size_t b = 0; b < sc.occupied.size(); ++b) {
        const std::uint64_t at = io.offset();
        io.value(sc.occupied[b], f.occupied);
        io.check(sc.occupied[b] <= 1, f.occupied, at, "must be 0 or 1");
    }
}

// settings: the file header's; version: the file's.
template <class IO, class K>
void keyframe(IO& io, K& k, const DescriptorSettings& settings, std::uint32_t version) {
    io.value(k.session, "session");
    io.value(k.node, "node");
    io.value(k.data.id, "id");
    io.value(k.data.scan_index, "scan_index");
    io.value(k.data.local_map_id, "local_map_id");
    io.value(k.data.stamp, "stamp");
    pose(io, k.data.T_odom_lidar, "T_odom_lidar");
    pose(io, k.data.T_anchor_lidar, "T_anchor_lidar");
    descriptor(io, k.descriptor, settings.loop, kLoopFields, false);
    // Format 2: the localisation descriptor (empty in keyframes of a continued format-1 map).
    if (version >= 2) {
        descriptor(io, k.localisation_descriptor, settings.localisation, kLocalisationFields, true);
    }
    const std::uint64_t at_p = io.offset();
    std::uint32_t n_points = static_cast<std::uint32_t>(k.data.points.size());
    io.value(n_points, "point_count");
    if constexpr (IO::kReading) {
        io.check(std::uint64_t(n_points) * 12 == io.remaining(), "point_count", at_p, [&] {
            return std::to_string(n_points) + " points do not fill the " +
                   std::to_string(io.remaining()) + " bytes left in the section";
        });
        k.data.points.resize(n_points);
    }
    for (std::uint32_t p = 0; p < n_points; ++p) vec3(io, k.data.points[p], "points");
}

bool same_shape(const places::ScanContextConfig& a, const places::ScanContextConfig& b) {
    return a.kind == b.kind && a.rings == b.rings && a.sectors == b.sectors;
}

// Writing: keyframes[first, first + count) of `list`; reading: appends them to `list`.
// expected: reading, the manifest's descriptor settings (checked when not null).
template <class IO, class S, class List, class V>
void keyframes_file(IO& io, S& settings, List& list, std::uint64_t& first, std::uint64_t& count,
                    const DescriptorSettings* expected, V& version) {
    file_start(io, kKeyframesMagic, "keyframes", version);
    io.section("header", [&](auto& h) {
        h.item("header");
        h.value(first, "first");
        const std::uint64_t at_count = h.offset();
        h.value(count, "count");
        const std::uint64_t at_cfg = h.offset();
        h.item("descriptor");
        descriptor_config(h, settings.loop);
        std::uint64_t at_local = at_cfg;
        if (version >= 2) {
            at_local = h.offset();
            h.item("localisation_descriptor");
            descriptor_config(h, settings.localisation);
        }
        if constexpr (IO::kReading) {
            if (version < 2) settings.localisation = no_localisation_descriptors();
            h.item("header");
            h.check(!expected || same_shape(settings.loop, expected->loop), "descriptor", at_cfg,
                    "descriptor settings differ from the manifest's");
            h.check(!expected || same_shape(settings.localisation, expected->localisation),
                    "localisation_descriptor", at_local,
                    "localisation descriptor settings differ from the manifest's");
            const std::size_t bins =
                std::size_t(settings.loop.rings) * std::size_t(settings.loop.sectors);
            // Format 4: compressed, at least a byte a keyframe.
            const std::uint64_t max_count =
                version >= 4 ? h.source_size() : h.source_size() / (100 + bins);
            h.check(count <= max_count, "count", at_count, "more keyframes than the file can hold");
            list.reserve(static_cast<std::size_t>(count));
        }
    });
    // One section a keyframe; format 4: those sections in one zstd frame (one section).
    const auto keyframe_sections = [&](auto& sub) {
        for (std::uint64_t j = 0; j < count; ++j) {
            const std::size_t i = static_cast<std::size_t>(first + j);
            const std::string name = "keyframes[" + std::to_string(i) + "]";
            if constexpr (std::decay_t<decltype(sub)>::kReading) {
                auto k = std::make_shared<StoredKeyframe>();
                sub.section(name, [&](auto& s) {
                    s.item("keyframes", i);
                    keyframe(s, *k, settings, version);
                });
                list.push_back(std::move(k));
            } else {
                sub.section(name, [&](auto& s) { keyframe(s, *list[i], settings, version); });
            }
        }
    };
    if (version < 4) {
        keyframe_sections(io);
        io.expect_end("end of file");
        return;
    }
    io.section("keyframes", [&](auto& s) {
        if constexpr (IO::kReading) {
            const std::uint64_t at = s.offset();
            const auto raw = s.template get<std::uint64_t>("keyframes");
            s.check(raw <= (std::uint64_t(1) << 30), "keyframes", at, "more than 1 GiB unpacked");
            std::vector<std::uint8_t> frame(std::size_t(s.remaining()));
            s.raw(frame.data(), frame.size(), "keyframes");
            const std::vector<std::uint8_t> bytes = common::zstd_decompress(
                frame.data(), frame.size(), std::size_t(raw), s.source(), "keyframes");
            // Offsets in errors from here on are in the unpacked bytes.
            ByteReader unpacked(s.source() + " (unpacked)", bytes.data(), bytes.size());
            keyframe_sections(unpacked);
            unpacked.expect_end("end of the keyframes");
        } else {
            ByteWriter unpacked;
            keyframe_sections(unpacked);
            const std::vector<std::uint8_t>& bytes = unpacked.bytes();
            s.value(std::uint64_t(bytes.size()));
            const std::vector<std::uint8_t> frame =
                common::zstd_compress(bytes.data(), bytes.size(), common::kColumnZstdLevel);
            s.raw(frame.data(), frame.size());
        }
    });
    io.expect_end("end of file");
}

}  // namespace

std::uint32_t map_format_for(const places::ScanContextConfig& localisation_descriptor_config,
                             bool records_sessions) {
    if (!has_localisation_descriptors(localisation_descriptor_config)) return 1u;
    return records_sessions ? kCompactMapFormatVersion : 2u;
}

std::string encode_local_map(const StoredLocalMap& map, std::uint32_t version) {
    ByteWriter w;
    local_map_file(w, map, *map.data, version);
    return as_string(w);
}

StoredLocalMap decode_local_map(const std::string& bytes, const std::string& file,
                                std::uint32_t* version) {
    ByteReader r(file, bytes.data(), bytes.size());
    StoredLocalMap m;
    auto d = std::make_shared<common::LocalMapData>();
    std::uint32_t v = 0;
    local_map_file(r, m, *d, v);
    m.data = std::move(d);
    if (version) *version = v;
    return m;
}

std::string encode_graph(std::uint64_t revision, const std::vector<PoseGraphNode>& nodes,
                         const std::vector<PoseGraphEdge>& edges, std::uint32_t version) {
    ByteWriter w;
    graph_file(w, revision, nodes, edges, version);
    return as_string(w);
}

void decode_graph(const std::string& bytes, const std::string& file, std::uint64_t* revision,
                  std::vector<PoseGraphNode>* nodes, std::vector<PoseGraphEdge>* edges,
                  std::uint32_t* version) {
    ByteReader r(file, bytes.data(), bytes.size());
    std::uint32_t v = 0;
    graph_file(r, *revision, *nodes, *edges, v);
    if (version) *version = v;
}

std::string encode_keyframes(const DescriptorSettings& settings,
                             const std::vector<std::shared_ptr<const StoredKeyframe>>& keyframes,
                             std::size_t first, std::size_t count, std::uint32_t version) {
    ByteWriter w;
    std::uint64_t first64 = first, count64 = count;
    if (version == 0 || !has_localisation_descriptors(settings.localisation))
        version = map_format_for(settings.localisation);
    keyframes_file(w, settings, keyframes, first64, count64, nullptr, version);
    return as_string(w);
}

std::vector<std::shared_ptr<const StoredKeyframe>> decode_keyframes(
    const std::string& bytes, const std::string& file, const DescriptorSettings* expected,
    std::uint64_t* first, std::uint32_t* version, DescriptorSettings* settings) {
    ByteReader r(file, bytes.data(), bytes.size());
    DescriptorSettings s;
    std::vector<std::shared_ptr<const StoredKeyframe>> out;
    std::uint64_t count = 0;
    std::uint32_t v = 0;
    keyframes_file(r, s, out, *first, count, expected, v);
    if (version) *version = v;
    if (settings) *settings = s;
    return out;
}

}  // namespace ltm::map
