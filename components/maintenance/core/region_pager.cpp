#include "maintenance/core/region_pager.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <system_error>

#include "common/core/byte_io.hpp"
#include "common/core/file_io.hpp"
#include "common/core/io_error.hpp"
#include "maintenance/core/region_io.hpp"

namespace ltm::maintenance {

namespace fs = std::filesystem;

namespace {

constexpr const char* kPrefix = "region_";

void write_plain(const std::string& path, const std::vector<std::uint8_t>& bytes) {
    // Scratch data of this run: no fsync (a crash loses the run, and the site's version is whole).
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    out.close();
    if (!out) throw common::IoError(path, "cannot write a paged-out region (disk full?)");
}

}  // namespace

RegionPager::RegionPager(std::string dir, const MaintenanceConfig& config)
    : dir_(std::move(dir)), config_(config) {
    std::error_code ec;
    fs::create_directories(dir_, ec);
    if (ec) throw common::IoError(dir_, "cannot create the paging folder: " + ec.message());
    for (const fs::directory_entry& e : fs::directory_iterator(dir_, ec)) {
        const std::string name = e.path().filename().string();
        if (name.rfind(kPrefix, 0) == 0) fs::remove(e.path(), ec);  // an earlier run's
    }
}

RegionPager::~RegionPager() {
    for (const auto& entry : regions_) std::remove(file_of(entry.first).c_str());
    std::error_code ec;
    if (fs::is_empty(dir_, ec) && !ec) fs::remove(dir_, ec);  // nothing of ours left in it
}

std::string RegionPager::file_of(const RegionKey& key) const {
    return dir_ + "/" + kPrefix + std::to_string(key.first) + "_" + std::to_string(key.second) +
           ".bin";
}

void RegionPager::page_out(const RegionKey& key, const ObservationMap& map) {
    common::ByteWriter w;
    write_region_section(w, key, map);
    page_out_section(key, w.bytes(), map.size());
}

void RegionPager::page_out_section(const RegionKey& key, const std::vector<std::uint8_t>& section,
                                   std::size_t voxels) {
    write_plain(file_of(key), section);
    regions_[key] = Paged{voxels, section.size()};
    ++pages_out_;
}

std::unique_ptr<ObservationMap> RegionPager::page_in(const RegionKey& key) {
    const auto it = regions_.find(key);
    if (it == regions_.end()) throw std::out_of_range("region not paged out");
    const std::string path = file_of(key);
    const std::string bytes = common::read_file(path, path);
    auto map = std::make_unique<ObservationMap>(config_, Eigen::Vector2i(key.first, key.second));
    map->reserve(it->second.voxels);
    common::ByteReader r(path, bytes.data(), bytes.size());
    read_region_section(r, kMaintainedMapVersion, float(config_.voxel_size),
                        [&](const RegionKey& read) -> ObservationMap& {
                            r.check(read == key, "region", 0, "another region's file");
                            return *map;
                        });
    r.expect_end("the region");
    std::remove(path.c_str());
    regions_.erase(it);
    ++pages_in_;
    return map;
}

std::vector<std::uint8_t> RegionPager::section(const RegionKey& key) const {
    const std::string path = file_of(key);
    const std::string bytes = common::read_file(path, path);
    return std::vector<std::uint8_t>(bytes.begin(), bytes.end());
}

std::size_t RegionPager::voxels() const {
    std::size_t n = 0;
    for (const auto& entry : regions_) n += entry.second.voxels;
    return n;
}

std::size_t RegionPager::disk_bytes() const {
    std::size_t n = 0;
    for (const auto& entry : regions_) n += entry.second.bytes;
    return n;
}

}  // namespace ltm::maintenance
