#include "evaluation/core/eval_io.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "common/core/io_error.hpp"
#include "common/core/point_labels.hpp"

namespace ltm::eval {
namespace {

std::string temp_file(const std::string& name, const std::string& text) {
    const std::string path = testing::TempDir() + "ltm_eval_io_" + name;
    std::ofstream(path) << text;
    return path;
}

TEST(EvalIo, LabelsRoundTrip) {
    const std::string path = testing::TempDir() + "ltm_eval_io_labels.label";
    const std::vector<std::uint32_t> labels = {common::make_label(common::kSimMovingActor, 4), 252u,
                                               0u};
    write_labels(path, labels);
    EXPECT_EQ(read_labels(path), labels);
    EXPECT_THROW(read_labels(temp_file("bad.label", "abc")), common::IoError);
    EXPECT_THROW(read_labels(path + ".missing"), common::IoError);
}

TEST(EvalIo, LoopPairs) {
    const auto loops =
        read_loop_pairs(temp_file("loops.txt", "# query match score\n12 3 0.5\n\n40 7\n"));
    ASSERT_EQ(loops.size(), 2u);
    EXPECT_EQ(loops[0].query, 12u);
    EXPECT_EQ(loops[0].match, 3u);
    EXPECT_DOUBLE_EQ(loops[0].score, 0.5);
    EXPECT_DOUBLE_EQ(loops[1].score, 0.0);
    EXPECT_THROW(read_loop_pairs(temp_file("loops_bad.txt", "12\n")), common::IoError);
    EXPECT_THROW(read_loop_pairs(temp_file("loops_neg.txt", "-1 4\n")), common::IoError);
}

TEST(EvalIo, RelocAttempts) {
    const auto a =
        read_reloc_attempts(temp_file("reloc.txt", "5 0.25 1 1 0 0 2 0 1 0 3 0 0 1 4\n7 1.5 0\n"));
    ASSERT_EQ(a.size(), 2u);
    EXPECT_EQ(a[0].frame, 5u);
    EXPECT_TRUE(a[0].has_pose);
    EXPECT_TRUE(a[0].pose.translation().isApprox(Eigen::Vector3d(2, 3, 4)));
    EXPECT_FALSE(a[1].has_pose);
    EXPECT_DOUBLE_EQ(a[1].time_s, 1.5);
    try {
        read_reloc_attempts(temp_file("reloc_bad.txt", "5 0.25 1 1 0 0\n"));
        FAIL() << "a short pose must be rejected";
    } catch (const common::IoError& e) {
        EXPECT_NE(std::string(e.what()).find("line 1"), std::string::npos);
    }
}

}  // namespace
}  // namespace ltm::eval
