#include "mapping/core/map_codec.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <unordered_set>

#include "mapping/core/binary_io.hpp"

namespace ltm::mapping {
namespace {

constexpr char kLocalMapMagic[8] = {'L', 'T', 'M', '-', 'L', 'M', 'A', 'P'};
constexpr char kGraphMagic[8] = {'L', 'T', 'M', '-', 'G', 'R', 'P', 'H'};
constexpr char kKeyframesMagic[8] = {'L', 'T', 'M', '-', 'K', 'F', 'R', 'M'};
constexpr std::size_t kChunk = 4096;

std::string range_name(const char* what, std::size_t a, std::size_t b) {
    std::ostringstream s;
    s << what << "[" << a << ".." << b << "]";
    return s.str();
}

std::string item(const std::string& what, std::size_t i, const char* field) {
    std::ostringstream s;
    s << what << "[" << i << "]." << field;
    return s.str();
}

void put_magic(ByteWriter& w, const char* magic) {
    w.put_bytes(magic, 8);
    w.put<std::uint32_t>(kMapFormatVersion);
}

void check_magic(ByteReader& r, const char* magic, const char* kind) {
    char m[8];
    r.get_bytes(m, 8, "magic");
    if (std::memcmp(m, magic, 8) != 0)
        r.fail_at("magic", 0, std::string("not an ltm ") + kind + " file");
    const std::uint64_t at = r.offset();
    const std::uint32_t version = r.get<std::uint32_t>("format version");
    if (version != kMapFormatVersion) {
        r.fail_at("format version", at,
                  "version " + std::to_string(version) + " is not supported (this build reads " +
                      std::to_string(kMapFormatVersion) + ")");
    }
}

float unit_interval(ByteReader& r, const std::string& field) {
    const std::uint64_t at = r.offset();
    const float v = r.get_f32(field);
    // Float rounding: |n_old . n_new| of two unit normals may come out a hair above 1.
    if (v < -1e-3f || v > 1.001f)
        r.fail_at(field, at, "must be in [0, 1] (got " + std::to_string(v) + ")");
    return v;
}

void put_descriptor_config(ByteWriter& w, const ScanContextConfig& c) {
    w.put<std::uint8_t>(std::uint8_t(c.kind));
    w.put<std::uint32_t>(std::uint32_t(c.rings));
    w.put<std::uint32_t>(std::uint32_t(c.sectors));
    w.put<double>(c.max_range);
    w.put<double>(c.min_range);
    w.put<double>(c.sensor_height);
}

ScanContextConfig get_descriptor_config(ByteReader& r) {
    ScanContextConfig c;
    const std::uint64_t at = r.offset();
    const std::uint8_t kind = r.get<std::uint8_t>("descriptor.kind");
    if (kind > 1) r.fail_at("descriptor.kind", at, "unknown kind " + std::to_string(kind));
    c.kind = ScanContextKind(kind);
    c.rings = int(r.get<std::uint32_t>("descriptor.rings"));
    c.sectors = int(r.get<std::uint32_t>("descriptor.sectors"));
    c.max_range = r.get_f64("descriptor.max_range");
    c.min_range = r.get_f64("descriptor.min_range");
    c.sensor_height = r.get_f64("descriptor.sensor_height");
    if (const auto problem = validate(c)) {
        r.fail_at("descriptor." + problem->key, at, problem->problem);
    }
    return c;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Local maps.

std::string encode_local_map(const StoredLocalMap& m) {
    const common::LocalMapData& d = *m.data;
    ByteWriter w;
    put_magic(w, kLocalMapMagic);
    w.begin_section();
    w.put<std::uint64_t>(m.node);
    w.put<std::uint32_t>(m.session);
    w.put<std::uint64_t>(d.id);
    w.put<std::uint32_t>(d.revision);
    w.put<std::uint8_t>(d.finished ? 1 : 0);
    w.put_pose(d.T_odom_anchor);
    w.put_pose(d.T_anchor_grid);
    w.put_vec3d(d.bbox_min);
    w.put_vec3d(d.bbox_max);
    w.put<float>(d.voxel_size);
    w.put<std::uint32_t>(std::uint32_t(d.observation_times.size()));
    w.put<std::uint64_t>(d.voxels.size());
    w.end_section();
    w.begin_section();
    for (const double t : d.observation_times) w.put<double>(t);
    w.end_section();
    for (std::size_t a = 0; a < d.voxels.size(); a += kChunk) {
        w.begin_section();
        for (std::size_t i = a; i < std::min(d.voxels.size(), a + kChunk); ++i) {
            const common::VoxelData& v = d.voxels[i];
            w.put_vec3i(v.index);
            w.put_vec3f(v.centre);
            w.put_vec3f(v.normal);
            w.put<std::uint32_t>(v.point_count);
            w.put<float>(v.planarity);
            w.put<float>(v.stability);
            w.put<double>(v.life.created);
            w.put<double>(v.life.last_seen);
            w.put<std::uint32_t>(v.life.observations);
            w.put<float>(v.life.health);
            w.put<std::uint16_t>(std::uint16_t(std::min<std::size_t>(v.life.seen.size(), 65535)));
            for (std::size_t k = 0; k < std::min<std::size_t>(v.life.seen.size(), 65535); ++k) {
                w.put<std::uint16_t>(v.life.seen[k]);
            }
        }
        w.end_section();
    }
    return std::move(w.bytes());
}

StoredLocalMap decode_local_map(const std::string& bytes, const std::string& file) {
    ByteReader r(file, bytes.data(), bytes.size());
    check_magic(r, kLocalMapMagic, "local map");
    StoredLocalMap m;
    auto d = std::make_shared<common::LocalMapData>();
    ByteReader h = r.section("header");
    m.node = h.get<std::uint64_t>("header.node");
    m.session = h.get<std::uint32_t>("header.session");
    d->id = h.get<std::uint64_t>("header.id");
    d->revision = h.get<std::uint32_t>("header.revision");
    const std::uint64_t at_finished = h.offset();
    const std::uint8_t finished = h.get<std::uint8_t>("header.finished");
    if (finished > 1) h.fail_at("header.finished", at_finished, "must be 0 or 1");
    d->finished = finished == 1;
    d->T_odom_anchor = h.get_pose("header.T_odom_anchor");
    d->T_anchor_grid = h.get_pose("header.T_anchor_grid");
    d->bbox_min = h.get_vec3d("header.bbox_min");
    const std::uint64_t at_max = h.offset();
    d->bbox_max = h.get_vec3d("header.bbox_max");
    if ((d->bbox_max.array() < d->bbox_min.array()).any()) {
        h.fail_at("header.bbox_max", at_max, "below bbox_min");
    }
    const std::uint64_t at_size = h.offset();
    d->voxel_size = h.get_f32("header.voxel_size");
    if (!(d->voxel_size > 0.0f)) h.fail_at("header.voxel_size", at_size, "must be > 0");
    const std::uint32_t n_times = h.get<std::uint32_t>("header.observation_count");
    const std::uint64_t at_voxels = h.offset();
    const std::uint64_t n_voxels = h.get<std::uint64_t>("header.voxel_count");
    h.expect_end("header");
    // Each voxel takes at least 74 bytes: a count beyond the file is damage, not a big map.
    if (n_voxels > bytes.size() / 74) {
        h.fail_at("header.voxel_count", at_voxels,
                  std::to_string(n_voxels) + " voxels cannot fit in a file of " +
                      std::to_string(bytes.size()) + " bytes");
    }
    ByteReader t = r.section("observation_times");
    d->observation_times.resize(n_times);
    for (std::uint32_t i = 0; i < n_times; ++i) {
        d->observation_times[i] = t.get_f64("observation_times[" + std::to_string(i) + "]");
    }
    t.expect_end("observation_times");
    d->voxels.resize(std::size_t(n_voxels));
    const float g = d->voxel_size;
    for (std::size_t a = 0; a < n_voxels; a += kChunk) {
        const std::size_t b = std::min<std::size_t>(n_voxels, a + kChunk);
        ByteReader s = r.section(range_name("voxels", a, b - 1));
        for (std::size_t i = a; i < b; ++i) {
            common::VoxelData& v = d->voxels[i];
            v.index = s.get_vec3i(item("voxels", i, "index"));
            const std::uint64_t at_c = s.offset();
            v.centre = s.get_vec3f(item("voxels", i, "centre"));
            const Eigen::Vector3f lo = v.index.cast<float>() * g;
            const float tol = std::max(1e-3f * g, 1e-6f * v.centre.cwiseAbs().maxCoeff());
            if (((v.centre - lo).array() < -tol).any() ||
                ((lo.array() + g - v.centre.array()) < -tol).any()) {
                s.fail_at(item("voxels", i, "centre"), at_c, "outside the voxel's cell");
            }
            const std::uint64_t at_n = s.offset();
            v.normal = s.get_vec3f(item("voxels", i, "normal"));
            const float nn = v.normal.norm();
            if (nn != 0.0f && std::abs(nn - 1.0f) > 1e-3f) {
                s.fail_at(item("voxels", i, "normal"), at_n, "neither zero nor a unit vector");
            }
            v.point_count = s.get<std::uint32_t>(item("voxels", i, "point_count"));
            v.planarity = unit_interval(s, item("voxels", i, "planarity"));
            v.stability = unit_interval(s, item("voxels", i, "stability"));
            v.life.created = s.get_f64(item("voxels", i, "life.created"));
            const std::uint64_t at_last = s.offset();
            v.life.last_seen = s.get_f64(item("voxels", i, "life.last_seen"));
            if (v.life.last_seen < v.life.created) {
                s.fail_at(item("voxels", i, "life.last_seen"), at_last, "before life.created");
            }
            v.life.observations = s.get<std::uint32_t>(item("voxels", i, "life.observations"));
            v.life.health = unit_interval(s, item("voxels", i, "life.health"));
            const std::uint16_t n_seen = s.get<std::uint16_t>(item("voxels", i, "life.seen count"));
            v.life.seen.resize(n_seen);
            for (std::uint16_t k = 0; k < n_seen; ++k) {
                const std::uint64_t at_k = s.offset();
                v.life.seen[k] = s.get<std::uint16_t>(item("voxels", i, "life.seen"));
                if (v.life.seen[k] >= n_times) {
                    s.fail_at(item("voxels", i, "life.seen"), at_k,
                              "index " + std::to_string(v.life.seen[k]) + " beyond the " +
                                  std::to_string(n_times) + " observation times");
                }
            }
        }
        s.expect_end(range_name("voxels", a, b - 1));
    }
    r.expect_end("end of file");
    m.data = std::move(d);
    return m;
}

// ---------------------------------------------------------------------------------------------
// The graph.

std::string encode_graph(std::uint64_t revision, const std::vector<PoseGraphNode>& nodes,
                         const std::vector<PoseGraphEdge>& edges) {
    ByteWriter w;
    put_magic(w, kGraphMagic);
    w.begin_section();
    w.put<std::uint64_t>(revision);
    w.put<std::uint64_t>(nodes.size());
    w.put<std::uint64_t>(edges.size());
    w.end_section();
    for (std::size_t a = 0; a < nodes.size(); a += kChunk) {
        w.begin_section();
        for (std::size_t i = a; i < std::min(nodes.size(), a + kChunk); ++i) {
            const PoseGraphNode& n = nodes[i];
            w.put<std::uint64_t>(n.id);
            w.put<std::uint64_t>(n.local_map_id);
            w.put<std::uint32_t>(n.session);
            w.put<std::uint8_t>(n.fixed ? 1 : 0);
            w.put_pose(n.T_odom_anchor);
            w.put_pose(n.T_world_anchor);
        }
        w.end_section();
    }
    for (std::size_t a = 0; a < edges.size(); a += kChunk) {
        w.begin_section();
        for (std::size_t i = a; i < std::min(edges.size(), a + kChunk); ++i) {
            const PoseGraphEdge& e = edges[i];
            w.put<std::uint64_t>(e.from);
            w.put<std::uint64_t>(e.to);
            w.put<std::uint8_t>(std::uint8_t(e.kind));
            w.put<std::uint8_t>(e.active ? 1 : 0);
            w.put_pose(e.T_from_to);
            for (int k = 0; k < 36; ++k) w.put<double>(e.information.data()[k]);
            w.put<std::uint64_t>(e.query_keyframe);
            w.put<std::uint64_t>(e.match_keyframe);
            w.put<double>(e.error_translation);
            w.put<double>(e.error_rotation);
        }
        w.end_section();
    }
    return std::move(w.bytes());
}

void decode_graph(const std::string& bytes, const std::string& file, std::uint64_t* revision,
                  std::vector<PoseGraphNode>* nodes, std::vector<PoseGraphEdge>* edges) {
    ByteReader r(file, bytes.data(), bytes.size());
    check_magic(r, kGraphMagic, "graph");
    ByteReader h = r.section("header");
    *revision = h.get<std::uint64_t>("header.revision");
    const std::uint64_t at_n = h.offset();
    const std::uint64_t n_nodes = h.get<std::uint64_t>("header.node_count");
    const std::uint64_t at_e = h.offset();
    const std::uint64_t n_edges = h.get<std::uint64_t>("header.edge_count");
    h.expect_end("header");
    if (n_nodes > bytes.size() / 200)
        h.fail_at("header.node_count", at_n, "more nodes than the file can hold");
    if (n_edges > bytes.size() / 400)
        h.fail_at("header.edge_count", at_e, "more edges than the file can hold");
    nodes->assign(std::size_t(n_nodes), PoseGraphNode());
    std::unordered_set<std::uint64_t> ids;
    for (std::size_t a = 0; a < n_nodes; a += kChunk) {
        const std::size_t b = std::min<std::size_t>(n_nodes, a + kChunk);
        ByteReader s = r.section(range_name("nodes", a, b - 1));
        for (std::size_t i = a; i < b; ++i) {
            PoseGraphNode& n = (*nodes)[i];
            const std::uint64_t at_id = s.offset();
            n.id = s.get<std::uint64_t>(item("nodes", i, "id"));
            if (!ids.insert(n.id).second) {
                s.fail_at(item("nodes", i, "id"), at_id,
                          "node id " + std::to_string(n.id) + " repeated");
            }
            n.local_map_id = s.get<std::uint64_t>(item("nodes", i, "local_map_id"));
            n.session = s.get<std::uint32_t>(item("nodes", i, "session"));
            const std::uint64_t at_f = s.offset();
            const std::uint8_t fixed = s.get<std::uint8_t>(item("nodes", i, "fixed"));
            if (fixed > 1) s.fail_at(item("nodes", i, "fixed"), at_f, "must be 0 or 1");
            n.fixed = fixed == 1;
            n.T_odom_anchor = s.get_pose(item("nodes", i, "T_odom_anchor"));
            n.T_world_anchor = s.get_pose(item("nodes", i, "T_world_anchor"));
        }
        s.expect_end(range_name("nodes", a, b - 1));
    }
    edges->assign(std::size_t(n_edges), PoseGraphEdge());
    for (std::size_t a = 0; a < n_edges; a += kChunk) {
        const std::size_t b = std::min<std::size_t>(n_edges, a + kChunk);
        ByteReader s = r.section(range_name("edges", a, b - 1));
        for (std::size_t i = a; i < b; ++i) {
            PoseGraphEdge& e = (*edges)[i];
            const std::uint64_t at_from = s.offset();
            e.from = s.get<std::uint64_t>(item("edges", i, "from"));
            if (!ids.count(e.from))
                s.fail_at(item("edges", i, "from"), at_from, "no node " + std::to_string(e.from));
            const std::uint64_t at_to = s.offset();
            e.to = s.get<std::uint64_t>(item("edges", i, "to"));
            if (!ids.count(e.to))
                s.fail_at(item("edges", i, "to"), at_to, "no node " + std::to_string(e.to));
            if (e.to == e.from)
                s.fail_at(item("edges", i, "to"), at_to, "an edge from a node to itself");
            const std::uint64_t at_k = s.offset();
            const std::uint8_t kind = s.get<std::uint8_t>(item("edges", i, "kind"));
            if (kind > 1)
                s.fail_at(item("edges", i, "kind"), at_k, "unknown kind " + std::to_string(kind));
            e.kind = EdgeKind(kind);
            const std::uint64_t at_a = s.offset();
            const std::uint8_t active = s.get<std::uint8_t>(item("edges", i, "active"));
            if (active > 1) s.fail_at(item("edges", i, "active"), at_a, "must be 0 or 1");
            e.active = active == 1;
            e.T_from_to = s.get_pose(item("edges", i, "T_from_to"));
            const std::uint64_t at_i = s.offset();
            for (int k = 0; k < 36; ++k)
                e.information.data()[k] = s.get_f64(item("edges", i, "information"));
            if ((e.information - e.information.transpose()).cwiseAbs().maxCoeff() >
                    1e-9 * std::max(1.0, e.information.cwiseAbs().maxCoeff()) ||
                (e.information.diagonal().array() < 0.0).any()) {
                s.fail_at(item("edges", i, "information"), at_i,
                          "not a symmetric information matrix");
            }
            e.query_keyframe = s.get<std::uint64_t>(item("edges", i, "query_keyframe"));
            e.match_keyframe = s.get<std::uint64_t>(item("edges", i, "match_keyframe"));
            e.error_translation = s.get_f64(item("edges", i, "error_translation"));
            e.error_rotation = s.get_f64(item("edges", i, "error_rotation"));
        }
        s.expect_end(range_name("edges", a, b - 1));
    }
    r.expect_end("end of file");
}

// ---------------------------------------------------------------------------------------------
// Keyframes.

std::string encode_keyframes(const ScanContextConfig& config,
                             const std::vector<std::shared_ptr<const StoredKeyframe>>& keyframes,
                             std::size_t first, std::size_t count) {
    ByteWriter w;
    put_magic(w, kKeyframesMagic);
    w.begin_section();
    w.put<std::uint64_t>(first);
    w.put<std::uint64_t>(count);
    put_descriptor_config(w, config);
    w.end_section();
    for (std::size_t i = first; i < first + count; ++i) {
        const StoredKeyframe& k = *keyframes[i];
        w.begin_section();
        w.put<std::uint32_t>(k.session);
        w.put<std::uint64_t>(k.node);
        w.put<std::uint64_t>(k.data.id);
        w.put<std::uint64_t>(k.data.scan_index);
        w.put<std::uint64_t>(k.data.local_map_id);
        w.put<double>(k.data.stamp);
        w.put_pose(k.data.T_odom_lidar);
        w.put_pose(k.data.T_anchor_lidar);
        const ScanContext& sc = k.descriptor;
        w.put<std::uint8_t>(std::uint8_t(sc.kind));
        w.put<std::uint32_t>(std::uint32_t(sc.rings));
        w.put<std::uint32_t>(std::uint32_t(sc.sectors));
        w.put_bytes(sc.value.data(), sc.value.size() * sizeof(float));
        if (sc.kind == ScanContextKind::kMeanVariance) {
            w.put_bytes(sc.spread.data(), sc.spread.size() * sizeof(float));
        }
        w.put_bytes(sc.occupied.data(), sc.occupied.size());
        w.put<std::uint32_t>(std::uint32_t(k.data.points.size()));
        for (const Eigen::Vector3f& p : k.data.points) w.put_vec3f(p);
        w.end_section();
    }
    return std::move(w.bytes());
}

std::vector<std::shared_ptr<const StoredKeyframe>> decode_keyframes(
    const std::string& bytes, const std::string& file, const ScanContextConfig* expected,
    std::uint64_t* first) {
    ByteReader r(file, bytes.data(), bytes.size());
    check_magic(r, kKeyframesMagic, "keyframes");
    ByteReader h = r.section("header");
    *first = h.get<std::uint64_t>("header.first");
    const std::uint64_t at_count = h.offset();
    const std::uint64_t count = h.get<std::uint64_t>("header.count");
    const std::uint64_t at_cfg = h.offset();
    const ScanContextConfig cfg = get_descriptor_config(h);
    h.expect_end("header");
    if (expected && (cfg.kind != expected->kind || cfg.rings != expected->rings ||
                     cfg.sectors != expected->sectors)) {
        h.fail_at("header.descriptor", at_cfg, "descriptor settings differ from the manifest's");
    }
    const std::size_t bins = std::size_t(cfg.rings) * std::size_t(cfg.sectors);
    if (count > bytes.size() / (100 + bins))
        h.fail_at("header.count", at_count, "more keyframes than the file can hold");
    std::vector<std::shared_ptr<const StoredKeyframe>> out;
    out.reserve(std::size_t(count));
    for (std::uint64_t j = 0; j < count; ++j) {
        const std::size_t i = std::size_t(*first + j);
        ByteReader s = r.section("keyframes[" + std::to_string(i) + "]");
        auto k = std::make_shared<StoredKeyframe>();
        k->session = s.get<std::uint32_t>(item("keyframes", i, "session"));
        k->node = s.get<std::uint64_t>(item("keyframes", i, "node"));
        k->data.id = s.get<std::uint64_t>(item("keyframes", i, "id"));
        k->data.scan_index = s.get<std::uint64_t>(item("keyframes", i, "scan_index"));
        k->data.local_map_id = s.get<std::uint64_t>(item("keyframes", i, "local_map_id"));
        k->data.stamp = s.get_f64(item("keyframes", i, "stamp"));
        k->data.T_odom_lidar = s.get_pose(item("keyframes", i, "T_odom_lidar"));
        k->data.T_anchor_lidar = s.get_pose(item("keyframes", i, "T_anchor_lidar"));
        ScanContext& sc = k->descriptor;
        const std::uint64_t at_d = s.offset();
        sc.kind = ScanContextKind(s.get<std::uint8_t>(item("keyframes", i, "descriptor.kind")));
        sc.rings = int(s.get<std::uint32_t>(item("keyframes", i, "descriptor.rings")));
        sc.sectors = int(s.get<std::uint32_t>(item("keyframes", i, "descriptor.sectors")));
        if (sc.kind != cfg.kind || sc.rings != cfg.rings || sc.sectors != cfg.sectors) {
            s.fail_at(item("keyframes", i, "descriptor"), at_d,
                      "shape differs from the file header's");
        }
        sc.value.resize(bins);
        for (std::size_t b = 0; b < bins; ++b) {
            const std::uint64_t at_v = s.offset();
            sc.value[b] = s.get_f32(item("keyframes", i, "descriptor.value"));
            if (sc.kind == ScanContextKind::kMaxHeight && sc.value[b] < 0.0f) {
                s.fail_at(item("keyframes", i, "descriptor.value"), at_v, "negative height");
            }
        }
        if (sc.kind == ScanContextKind::kMeanVariance) {
            sc.spread.resize(bins);
            for (std::size_t b = 0; b < bins; ++b) {
                const std::uint64_t at_v = s.offset();
                sc.spread[b] = s.get_f32(item("keyframes", i, "descriptor.spread"));
                if (sc.spread[b] < 0.0f)
                    s.fail_at(item("keyframes", i, "descriptor.spread"), at_v, "negative");
            }
        }
        sc.occupied.resize(bins);
        for (std::size_t b = 0; b < bins; ++b) {
            const std::uint64_t at_o = s.offset();
            sc.occupied[b] = s.get<std::uint8_t>(item("keyframes", i, "descriptor.occupied"));
            if (sc.occupied[b] > 1)
                s.fail_at(item("keyframes", i, "descriptor.occupied"), at_o, "must be 0 or 1");
        }
        const std::uint64_t at_p = s.offset();
        const std::uint32_t n_points = s.get<std::uint32_t>(item("keyframes", i, "point_count"));
        if (std::uint64_t(n_points) * 12 != s.remaining()) {
            s.fail_at(item("keyframes", i, "point_count"), at_p,
                      std::to_string(n_points) + " points do not fill the " +
                          std::to_string(s.remaining()) + " bytes left in the section");
        }
        k->data.points.resize(n_points);
        for (std::uint32_t p = 0; p < n_points; ++p) {
            k->data.points[p] = s.get_vec3f(item("keyframes", i, "points"));
        }
        s.expect_end("keyframes[" + std::to_string(i) + "]");
        out.push_back(std::move(k));
    }
    r.expect_end("end of file");
    return out;
}

}  // namespace ltm::mapping
