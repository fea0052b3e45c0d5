// Fuzz target: PCD files through load_cloud_file (common/core/pcl_cloud_io, PCL underneath). It
// takes a path, so the input is written to a scratch file named *.pcd. Promise: a consistent cloud
// or a one-line IoError; never a crash inside PCL.
#include <cstddef>
#include <cstdint>

#include "common/core/io_error.hpp"
#include "common/core/pcl_cloud_io.hpp"
#include "fuzz_util.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string path = ltm::fuzz::write_input(data, size, "cloud.pcd");
    try {
        const ltm::common::PointCloud cloud = ltm::common::load_cloud_file(path);
        if (!cloud.consistent()) ltm::fuzz::finding("a cloud whose channels differ in size");
    } catch (const ltm::common::IoError& e) {
        ltm::fuzz::expect_one_line(e);
    }
    return 0;
}
