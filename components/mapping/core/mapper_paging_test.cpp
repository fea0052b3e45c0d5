// Paging the local maps (mapper_paging.cpp, PagingConfig): a Mapper whose far local maps left
// memory after a save loads them back for a loop, a fold and an edit, and ends with the same saved
// map as one that kept them all; a damaged file on the way back is one line, and the map on disk
// keeps that local map's file as it was.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>

#include "common/core/file_io.hpp"
#include "map/core/map_codec.hpp"
#include "map/core/map_store.hpp"
#include "mapping/core/mapper.hpp"
#include "mapping/core/mapper_test_drive.hpp"
#include "registration/core/test_data.hpp"

namespace ltm::mapping {
namespace {

namespace fs = std::filesystem;
using test::Drive;
using test::replay;
using test::test_config;

fs::path fresh_dir(const std::string& name) {
    const fs::path p = fs::temp_directory_path() / ("ltm_mapper_paging_" + name);
    fs::remove_all(p);
    return p;
}

// The files of a saved map (named by their content): the same set, the same map.
std::set<std::string> files_of(const fs::path& dir) {
    std::set<std::string> out;
    for (const auto& e : fs::recursive_directory_iterator(dir))
        if (e.is_regular_file()) out.insert(fs::relative(e.path(), dir).string());
    return out;
}

struct Outcome {
    std::set<std::string> files;  // of the final save
    std::size_t paged_out = 0;    // after the first lap's save
    std::size_t paged_in = 0;     // by the end
    std::size_t loops = 0;
    std::size_t local_maps = 0;
    std::size_t memory_full = 0, memory_paged = 0;  // Mapper::memory_bytes before / after paging
    std::vector<std::string> problems;
};

// Paging beyond 20 m (the test drives are a few tens of metres long).
MapperConfig paging_config() {
    MapperConfig config = test_config();
    config.paging.radius = 20.0;
    return config;
}

// Paging on: a paged-out local map is read back from its file in `dir`.
void read_back_from(Mapper& mapper, const fs::path& dir) {
    mapper.set_local_map_loader(
        [dir](const map::LocalMapFile& f) { return map::load_local_map(dir.string(), f).data; });
}

// A lap east, a save, (paging with a 20 m radius), a second lap back over the first (loops
// verified against its maps and folds into them), an edit on the first lap's maps, a save.
// `damage` flips a byte of node 0's file once it is paged out.
Outcome run(const fs::path& dir, bool paging, bool damage = false) {
    const std::vector<Eigen::Vector3f> scene =
        registration::test::with_dense_ground(registration::test::synthetic_scene(71));
    Mapper mapper(paging_config());
    if (paging) read_back_from(mapper, dir);
    map::MapWriter writer(dir.string());
    Outcome out;
    replay(Drive(scene, 0.0, 0.0, Eigen::Isometry3d::Identity(), 0.0), mapper);
    writer.save(mapper.snapshot());
    out.memory_full = mapper.memory_bytes();
    out.paged_out = mapper.page_out(writer.written_local_maps());
    out.memory_paged = mapper.memory_bytes();
    if (damage) {
        const auto w = writer.written_local_maps().find(0);
        EXPECT_NE(w, writer.written_local_maps().end());
        const std::string path = (dir / w->second.file->file).string();
        std::string bytes = common::read_file(path, "lm");
        bytes[bytes.size() / 2] = char(bytes[bytes.size() / 2] ^ 0x5a);
        std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
    }
    const Drive lap2(scene, 0.5, 0.3, registration::test::xy_yaw(0.3, -0.2, 1.0), 100.0, 1000,
                     Eigen::Isometry3d::Identity(), 4);
    replay(lap2, mapper);
    std::vector<Eigen::Vector3f> centres;  // cells on the first lap's road
    for (float x = 8.0f; x <= 30.0f; x += 0.5f)
        for (float y = -10.0f; y <= 10.0f; y += 0.5f) centres.emplace_back(x, y, 1.0f);
    mapper.remove_cells(centres, 0.5f);
    writer.save(mapper.snapshot());
    out.files = files_of(dir);
    out.paged_in = mapper.paged_in();
    out.loops = mapper.loops().size();
    out.local_maps = mapper.local_map_count();
    out.problems = mapper.take_paging_problems();
    return out;
}

TEST(MapperPaging, FarLocalMapsLeaveAfterASaveAndComeBackWithTheSameSavedMap) {
    const Outcome whole = run(fresh_dir("whole"), false);
    const Outcome paged = run(fresh_dir("paged"), true);
    EXPECT_EQ(whole.paged_out, 0u);  // no loader: nothing is paged
    // Anchors at x = 0, 12, 24, 36; the last keyframe at x = 45: three beyond 20 m.
    EXPECT_EQ(paged.paged_out, 3u);
    EXPECT_LT(paged.memory_paged * 2, paged.memory_full);
    EXPECT_GE(paged.paged_in, 2u);  // the second lap's loops, folds and the edit read them back
    EXPECT_TRUE(paged.problems.empty()) << paged.problems.front();
    EXPECT_GT(paged.loops, 0u);
    EXPECT_EQ(paged.loops, whole.loops);
    EXPECT_EQ(paged.local_maps, whole.local_maps);
    EXPECT_EQ(paged.files, whole.files);  // content-named: the same graph, keyframes, local maps
}

TEST(MapperPaging, ADamagedFileOnTheWayBackIsOneLineAndTheMapOnDiskKeepsIt) {
    const fs::path dir = fresh_dir("damaged");
    const Outcome o = run(dir, true, true);
    ASSERT_EQ(o.problems.size(), 1u);
    EXPECT_NE(o.problems[0].find("local map of node 0 unavailable"), std::string::npos)
        << o.problems[0];
    EXPECT_EQ(o.problems[0].find('\n'), std::string::npos);
    // The save kept node 0's file (not an empty map over it): the load refuses that one file,
    // named, and loads the rest.
    const map::LoadedMap loaded = map::load_map(dir.string());
    ASSERT_EQ(loaded.refused.size(), 1u);
    EXPECT_NE(loaded.refused[0].find("lm_00000000_"), std::string::npos) << loaded.refused[0];
    EXPECT_EQ(loaded.map.local_maps.size() + 1, o.local_maps);
}

TEST(MapperPaging, ASaveElsewhereReadsThePagedOutMapsBack) {
    const std::vector<Eigen::Vector3f> scene =
        registration::test::with_dense_ground(registration::test::synthetic_scene(71));
    Mapper mapper(paging_config());
    const fs::path dir = fresh_dir("elsewhere");
    read_back_from(mapper, dir);
    replay(Drive(scene, 0.0, 0.0, Eigen::Isometry3d::Identity(), 0.0), mapper);
    map::MapWriter writer(dir.string());
    writer.save(mapper.snapshot());
    const std::set<std::string> before = files_of(dir);
    ASSERT_EQ(mapper.page_out(writer.written_local_maps()), 3u);
    // Into the same directory: its files kept, nothing written but the manifest.
    const map::SaveStats again = writer.save(mapper.snapshot());
    EXPECT_EQ(again.files_written, 1u);
    EXPECT_EQ(files_of(dir), before);
    // Elsewhere: whole, the same files.
    const fs::path other = fresh_dir("elsewhere_copy");
    map::save_map(other.string(), mapper.complete_snapshot());
    EXPECT_EQ(files_of(other), before);
    EXPECT_EQ(mapper.paged_out(), 3u);  // read for the save, not kept
    // The global map is the same with the maps paged out.
    Mapper whole(paging_config());
    replay(Drive(scene, 0.0, 0.0, Eigen::Isometry3d::Identity(), 0.0), whole);
    EXPECT_EQ(mapper.global_map().points.size(), whole.global_map().points.size());
}

// Maintenance edits that reach paged-out local maps (issue 28 item 3: the open miss of the first
// day-1 runs): cells recorded while the maps they cover are on disk, a page-out while the clearing
// waits, a save between the steps, cells kept again, a second lap whose snapshots are cleared on
// arrival and fold into maps read back, one-shot edits after; every local map ends bit for bit as
// the Mapper that kept them all has it (encoded, the lossless row format), with the same count of
// voxels cleared. Deterministic: the calls are the same, only the paging differs.
struct EditOutcome {
    std::map<std::uint64_t, std::string> local_maps;  // node -> encoded
    std::map<std::uint64_t, std::size_t> voxels;      // node -> voxel count (readable failures)
    std::size_t removed = 0, loops = 0, paged_out = 0, paged_in = 0;
};

void edits_on_paged_maps(const fs::path& dir, bool paging, EditOutcome* result) {
    EditOutcome& out = *result;
    const std::vector<Eigen::Vector3f> scene =
        registration::test::with_dense_ground(registration::test::synthetic_scene(71));
    Mapper mapper(paging_config());
    if (paging) read_back_from(mapper, dir);
    map::MapWriter writer(dir.string());
    const auto cells = [](float x0, float x1, float y0, float y1, float z) {
        std::vector<Eigen::Vector3f> c;
        for (float x = x0; x <= x1; x += 0.5f)
            for (float y = y0; y <= y1; y += 0.5f) c.emplace_back(x, y, z);
        return c;
    };
    replay(Drive(scene, 0.0, 0.0, Eigen::Isometry3d::Identity(), 0.0), mapper);
    writer.save(mapper.snapshot());
    out.paged_out += mapper.page_out(writer.written_local_maps());
    // Recorded while nodes 0-2 are on disk; a page-out before the steps (the waiting maps stay).
    mapper.remove_cells_in_steps(cells(2.0f, 30.0f, -12.0f, 12.0f, 0.25f), 0.5f);
    out.paged_out += mapper.page_out(writer.written_local_maps());
    ASSERT_TRUE(mapper.clear_removed_step());  // one map cleared, the rest wait over a save
    writer.save(mapper.snapshot());
    out.paged_out += mapper.page_out(writer.written_local_maps());
    while (mapper.clear_removed_step()) {
    }
    writer.save(mapper.snapshot());
    out.paged_out += mapper.page_out(writer.written_local_maps());
    // New objects where some cells were: kept; then cells elsewhere, at once.
    mapper.keep_cells(cells(10.0f, 14.0f, -12.0f, 12.0f, 0.25f), 0.5f);
    mapper.remove_cells(cells(0.0f, 20.0f, -12.0f, 12.0f, 1.25f), 0.5f);
    // As the component pages, before its next save: the maps this edit changed are not on disk
    // as they are now and stay.
    out.paged_out += mapper.page_out(writer.written_local_maps());
    writer.save(mapper.snapshot());
    out.paged_out += mapper.page_out(writer.written_local_maps());
    // The second lap: snapshots cleared on arrival, folded into the first lap's maps.
    const Drive lap2(scene, 0.5, 0.3, registration::test::xy_yaw(0.3, -0.2, 1.0), 100.0, 1000,
                     Eigen::Isometry3d::Identity(), 4);
    replay(lap2, mapper);
    out.paged_out += mapper.page_out(writer.written_local_maps());
    mapper.remove_cells(cells(20.0f, 45.0f, -12.0f, 12.0f, 0.75f), 0.5f);
    out.paged_out += mapper.page_out(writer.written_local_maps());
    writer.save(mapper.snapshot());
    out.paged_out += mapper.page_out(writer.written_local_maps());
    for (const map::StoredLocalMap& m : mapper.complete_snapshot().local_maps) {
        out.local_maps[m.node] = map::encode_local_map(m);
        out.voxels[m.node] = m.data->voxels.size();
    }
    out.removed = mapper.removed_voxels();
    out.loops = mapper.loops().size();
    out.paged_in = mapper.paged_in();
    EXPECT_TRUE(mapper.take_paging_problems().empty());
}

TEST(MapperPaging, EditsReachingPagedOutMapsLeaveTheSameVoxelsAsWithoutPaging) {
    EditOutcome whole, paged;
    ASSERT_NO_FATAL_FAILURE(edits_on_paged_maps(fresh_dir("edits_whole"), false, &whole));
    ASSERT_NO_FATAL_FAILURE(edits_on_paged_maps(fresh_dir("edits_paged"), true, &paged));
    EXPECT_EQ(whole.paged_out, 0u);
    EXPECT_GE(paged.paged_out, 4u);  // the first lap's far maps, and again after their edits
    EXPECT_GE(paged.paged_in, 3u);   // read back by the edits and the second lap
    EXPECT_GT(whole.removed, 0u);
    EXPECT_EQ(paged.removed, whole.removed);
    EXPECT_EQ(paged.loops, whole.loops);
    EXPECT_EQ(paged.voxels, whole.voxels);
    EXPECT_TRUE(paged.local_maps == whole.local_maps);  // bit for bit
}

TEST(MapperPaging, RadiusIsValidated) {
    MapperConfig config = test_config();
    config.paging.radius = -1.0;
    EXPECT_THROW(Mapper{config}, common::ConfigError);
}

}  // namespace
}  // namespace ltm::mapping
