// Fuzz target: the KITTI readers (common/core/kitti_io): a velodyne .bin scan, and the same bytes
// as times.txt and calib.txt. They take a path, so the input is written to a scratch file.
// Promise: a cloud (one point per 16 bytes, intensity for each) or a one-line IoError.
#include <cstddef>
#include <cstdint>

#include "common/core/io_error.hpp"
#include "common/core/kitti_io.hpp"
#include "fuzz_util.hpp"

using ltm::common::IoError;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string path = ltm::fuzz::write_input(data, size, "scan.bin");
    try {
        const ltm::common::PointCloud cloud = ltm::common::read_kitti_bin(path);
        if (cloud.size() * 16 != size || !cloud.consistent() ||
            cloud.intensity.size() != cloud.size())
            ltm::fuzz::finding("a .bin of " + std::to_string(size) + " bytes read as " +
                               std::to_string(cloud.size()) + " points");
    } catch (const IoError& e) {
        ltm::fuzz::expect_one_line(e);
    }
    try {
        ltm::common::read_times(path);
    } catch (const IoError& e) {
        ltm::fuzz::expect_one_line(e);
    }
    try {
        ltm::common::read_kitti_calib_tr(path);
    } catch (const IoError& e) {
        ltm::fuzz::expect_one_line(e);
    }
    return 0;
}
