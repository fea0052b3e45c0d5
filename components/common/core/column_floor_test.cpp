#include "common/core/column_floor.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace ltm::common {
namespace {

// Each column keeps its lowest point; a neighbourhood's lowest is the least of its columns';
// columns are on the lattice through the origin (negative coordinates included); an empty
// neighbourhood and a non-finite point answer +infinity.
TEST(ColumnFloor, TheLowestOfTheColumnsAroundAPoint) {
    ColumnFloor floor(1.0f);
    floor.add(Eigen::Vector3f(0.5f, 0.5f, 2.0f));
    floor.add(Eigen::Vector3f(0.2f, 0.9f, 1.0f));   // same column, lower
    floor.add(Eigen::Vector3f(0.7f, 0.1f, 3.0f));   // same column, higher: kept 1.0
    floor.add(Eigen::Vector3f(2.5f, 0.5f, -1.0f));  // two columns east
    floor.add(Eigen::Vector3f(-0.5f, 0.5f, 0.5f));  // the column west of the origin
    floor.add(Eigen::Vector3f(std::nanf(""), 0.5f, -9.0f));
    const float inf = std::numeric_limits<float>::infinity();
    EXPECT_FLOAT_EQ(floor.lowest_around(Eigen::Vector3f(0.5f, 0.5f, 9.0f), 0), 1.0f);
    EXPECT_FLOAT_EQ(floor.lowest_around(Eigen::Vector3f(0.5f, 0.5f, 9.0f), 1), 0.5f);
    EXPECT_FLOAT_EQ(floor.lowest_around(Eigen::Vector3f(0.5f, 0.5f, 9.0f), 2), -1.0f);
    EXPECT_FLOAT_EQ(floor.lowest_around(Eigen::Vector3f(-0.1f, 0.5f, 0.0f), 0), 0.5f);
    EXPECT_EQ(floor.lowest_around(Eigen::Vector3f(10.5f, 0.5f, 0.0f), 2), inf);
    EXPECT_EQ(floor.lowest_around(Eigen::Vector3f(std::nanf(""), 0.5f, 0.0f), 2), inf);
}

}  // namespace
}  // namespace ltm::common
