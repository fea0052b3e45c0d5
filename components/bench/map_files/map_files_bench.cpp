// ltm_bench_map_files VERSION [--out D] [--repeat N]: where the bytes of a site version are (its
// map's keyframes, local maps, graph, manifest; its maintained state) and how long the robot takes
// to load them (issue 26: at most 100 MB of map and maintained state a km of new ground; the
// robot's start-up). With --out, the version is saved again in this build's formats under D
// (D/map, D/maintenance/long_term_map.bin), its sizes and load times printed beside the original's,
// and every local map, keyframe and maintained voxel compared bit for bit (exit 1 if one differs).
// With --against PREV (the version before it), where the growth went (issue 26, repeated ground):
// keyframes by session, voxels of each local map before and after, and the maintained voxels
// added and gone (the added ones by hits, height and the session that created them).
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "common/cli/cli.hpp"
#include "common/core/file_io.hpp"
#include "maintenance/core/long_term_map.hpp"
#include "map/core/map_codec.hpp"
#include "map/core/map_store.hpp"
#include "version_growth.hpp"

namespace fs = std::filesystem;
using ltm::maintenance::LongTermMap;

namespace {

struct Sizes {
    std::map<std::string, std::uint64_t> bytes;  // by file kind
    std::map<std::string, std::size_t> files;
};

std::string kind_of(const fs::path& p) {
    const std::string name = p.filename().string();
    if (name == "long_term_map.bin") return "maintained";
    if (name.rfind("keyframes_", 0) == 0) return "keyframes";
    if (name.rfind("lm_", 0) == 0) return "local_maps";
    if (name.rfind("graph_", 0) == 0) return "graph";
    if (name == "manifest.txt") return "manifest";
    return "other";
}

Sizes sizes_of(const std::string& dir) {
    Sizes s;
    for (const auto& e : fs::recursive_directory_iterator(dir)) {
        if (!e.is_regular_file()) continue;
        const std::string k = kind_of(e.path());
        if (k == "other") continue;
        s.bytes[k] += e.file_size();
        ++s.files[k];
    }
    return s;
}

// Median wall time of `repeat` runs of f [s].
double timed(int repeat, const std::function<void()>& f) {
    std::vector<double> t;
    for (int k = 0; k < repeat; ++k) {
        const auto a = std::chrono::steady_clock::now();
        f();
        t.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - a).count());
    }
    std::sort(t.begin(), t.end());
    return t[t.size() / 2];
}

struct Loads {
    double map_s = 0, maintained_s = 0, maintained_paged_s = 0;
};

Loads load_times(const std::string& version, int repeat,
                 const ltm::maintenance::MaintenanceConfig& c) {
    Loads l;
    l.map_s = timed(repeat, [&] { (void)ltm::map::load_map(version + "/map"); });
    const std::string maint = version + "/maintenance/long_term_map.bin";
    if (fs::exists(maint)) {
        l.maintained_s = timed(repeat, [&] { (void)LongTermMap::load(maint, c); });
        const std::string pages =
            (fs::temp_directory_path() / ("ltm_bench_map_files_" + std::to_string(::getpid())))
                .string();
        l.maintained_paged_s = timed(repeat, [&] {
            (void)LongTermMap::load(maint, c, ltm::maintenance::PagingConfig{100.0, pages});
        });
    }
    return l;
}

// What a local map's voxels record of their views: life.seen entries (indices into the map's
// observation times) over all voxels, and the maps' observation times.
struct SeenStats {
    std::size_t seen = 0, times = 0, maps = 0;
};

void print(const char* what, const Sizes& s, const Loads& l, std::size_t lm_voxels,
           std::size_t keyframes, std::size_t maint_voxels, const SeenStats& seen) {
    const auto mb = [](std::uint64_t b) { return double(b) / 1e6; };
    std::uint64_t total = 0;
    for (const auto& [k, b] : s.bytes) total += b;
    std::printf("%s: %.2f MB in all\n", what, mb(total));
    for (const auto& [k, b] : s.bytes) {
        std::printf("  %-11s %8.3f MB  %4zu files", k.c_str(), mb(b), s.files.at(k));
        if (k == "local_maps" && lm_voxels)
            std::printf("  %zu voxels, %.1f B a voxel, %.1f seen entries a voxel, %.0f times a map",
                        lm_voxels, double(b) / double(lm_voxels),
                        double(seen.seen) / double(lm_voxels),
                        seen.maps ? double(seen.times) / double(seen.maps) : 0.0);
        if (k == "keyframes" && keyframes)
            std::printf("  %zu keyframes, %.0f B a keyframe", keyframes,
                        double(b) / double(keyframes));
        if (k == "maintained" && maint_voxels)
            std::printf("  %zu voxels, %.1f B a voxel", maint_voxels,
                        double(b) / double(maint_voxels));
        std::printf("\n");
    }
    std::printf("  load: map %.3f s, maintained %.3f s (paged: %.3f s)\n", l.map_s, l.maintained_s,
                l.maintained_paged_s);
}

SeenStats seen_of(const ltm::map::MapData& m) {
    SeenStats s;
    for (const auto& lm : m.local_maps) {
        if (!lm.data) continue;
        ++s.maps;
        s.times += lm.data->observation_times.size();
        for (const auto& v : lm.data->voxels) s.seen += v.life.seen.size();
    }
    return s;
}

std::size_t voxels_of(const ltm::map::MapData& m) {
    std::size_t n = 0;
    for (const auto& lm : m.local_maps)
        if (lm.data) n += lm.data->voxels.size();
    return n;
}

}  // namespace

int main(int argc, char** argv) {
    std::string version, out;
    int repeat = 3;
    CLI::App app{
        "A site version's bytes by file kind and its load time; --out: saved again in "
        "this build's formats, compared bit for bit"};
    ltm::common::cli::configure(app);
    app.add_option("version", version, "a site version's folder (holding map/ and maintenance/)")
        ->required()
        ->check(CLI::ExistingDirectory);
    app.add_option("--out", out, "save the version again here (this build's formats)");
    std::string against;
    app.add_option("--against", against,
                   "the version before it: where the growth went (keyframes, local maps, "
                   "maintained voxels)")
        ->check(CLI::ExistingDirectory);
    app.add_option("--repeat", repeat, "loads timed (the median is printed)")
        ->check(ltm::common::cli::at_least(1));
    if (const int code = ltm::common::cli::parse(app, argc, argv); code >= 0) return code;
    try {
        const ltm::maintenance::MaintenanceConfig config;
        const ltm::map::LoadedMap loaded = ltm::map::load_map(version + "/map");
        for (const std::string& r : loaded.refused)
            std::fprintf(stderr, "refused: %s\n", r.c_str());
        const std::string maint = version + "/maintenance/long_term_map.bin";
        const bool has_maint = fs::exists(maint);
        std::size_t maint_voxels = 0;
        if (has_maint) maint_voxels = LongTermMap::load(maint, config).stats().voxels;
        print(version.c_str(), sizes_of(version), load_times(version, repeat, config),
              voxels_of(loaded.map), loaded.map.keyframes.size(), maint_voxels,
              seen_of(loaded.map));
        if (!against.empty()) ltm::bench::print_growth(against, version, config);
        if (out.empty()) return 0;

        fs::create_directories(out + "/maintenance");
        ltm::map::save_map(out + "/map", loaded.map);
        if (has_maint)
            LongTermMap::load(maint, config).save(out + "/maintenance/long_term_map.bin");
        const ltm::map::LoadedMap again = ltm::map::load_map(out + "/map");
        print(out.c_str(), sizes_of(out), load_times(out, repeat, config), voxels_of(again.map),
              again.map.keyframes.size(), maint_voxels, seen_of(again.map));

        // Bit for bit: every record encoded in one format (3) from both loads.
        std::size_t differ = 0;
        const auto& a = loaded.map;
        const auto& b = again.map;
        if (a.local_maps.size() != b.local_maps.size() || a.keyframes.size() != b.keyframes.size())
            ++differ;
        for (std::size_t i = 0; i < std::min(a.local_maps.size(), b.local_maps.size()); ++i)
            if (ltm::map::encode_local_map(a.local_maps[i], 3) !=
                ltm::map::encode_local_map(b.local_maps[i], 3))
                ++differ;
        const ltm::map::DescriptorSettings settings{a.descriptor_config,
                                                    a.localisation_descriptor_config};
        if (ltm::map::encode_keyframes(settings, a.keyframes, 0, a.keyframes.size(), 3) !=
            ltm::map::encode_keyframes(settings, b.keyframes, 0, b.keyframes.size(), 3))
            ++differ;
        if (ltm::map::encode_graph(a.revision, a.nodes, a.edges, 3) !=
            ltm::map::encode_graph(b.revision, b.nodes, b.edges, 3))
            ++differ;
        if (has_maint) {  // both saved by this build: the same bytes when every voxel is the same
            const std::string twice = out + "/maintenance/long_term_map.again.bin";
            LongTermMap::load(out + "/maintenance/long_term_map.bin", config).save(twice);
            if (ltm::common::read_file(twice, twice) !=
                ltm::common::read_file(out + "/maintenance/long_term_map.bin", "saved"))
                ++differ;
            fs::remove(twice);
        }
        std::printf("bit for bit: %s\n", differ == 0
                                             ? "the same (local maps, keyframes, graph, maintained)"
                                             : "DIFFERENT");
        return differ == 0 ? 0 : 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "ltm_bench_map_files: %s\n", e.what());
        return 2;
    }
}
