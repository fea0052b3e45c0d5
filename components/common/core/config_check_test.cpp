#include "common/core/config_check.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace ltm::common {
namespace {

struct Example {
    double size = 0.5;
    double limit = 10.0;
    double low = 0.25, high = 0.5;
    int count = 3;
    double spacing = 2.0;
    int factor = 0;
    std::string mode = "fast";
    std::vector<double> offsets = {0.0};
    bool flag = true;
    std::string label = "anything";
};

template <class Visitor>
void visit_fields(Example& c, Visitor&& v) {
    using namespace rules;
    v("size", c.size, positive);
    v("limit", c.limit, positive.or_infinite());
    v("low", c.low, non_negative);
    v("high", c.high, unit.or_infinite());  // in [0, 1]: infinity still outside
    v("count", c.count, in_range(1, 1000));
    v("spacing", c.spacing, above(1));
    v("factor", c.factor, zero_or_in(2, 16));
    v("mode", c.mode, one_of({"fast", "slow", "off"}));
    v("offsets", c.offsets, not_empty);
    v("flag", c.flag, unchecked);
    v("label", c.label, unchecked);
}

std::optional<ConfigProblem> validate(Example c) {
    ConfigChecker k;
    visit_fields(c, k);
    k.require(c.low < c.high, "high", "must exceed low");
    return k.problem();
}

std::string problem_of(const Example& c) {
    const auto p = validate(c);
    return p ? p->key + ": " + p->problem : "";
}

TEST(ConfigCheck, EachKindOfRuleNamesTheKeyAndTheValue) {
    EXPECT_EQ(problem_of(Example{}), "");
    Example c;
    c.high = 0.9;
    c.low = 0.5;
    EXPECT_EQ(problem_of(c), "") << "valid";
    const double inf = std::numeric_limits<double>::infinity();
    auto with = [](auto change) {
        Example e;
        change(e);
        return problem_of(e);
    };
    EXPECT_EQ(with([](Example& e) { e.size = 0.0; }), "size: must be > 0 (got 0)");
    EXPECT_EQ(with([&](Example& e) { e.size = inf; }), "size: must be > 0 (got inf)");
    EXPECT_EQ(with([](Example& e) { e.size = std::nan(""); }), "size: must be > 0 (got nan)");
    EXPECT_EQ(with([&](Example& e) { e.limit = inf; }), "") << "or_infinite";
    EXPECT_EQ(with([&](Example& e) { e.limit = -inf; }), "limit: must be > 0 (got -inf)");
    EXPECT_EQ(with([](Example& e) { e.limit = std::nan(""); }), "limit: must be > 0 (got nan)");
    EXPECT_EQ(with([](Example& e) { e.low = -0.5; }), "low: must be >= 0 (got -0.5)");
    EXPECT_EQ(with([](Example& e) { e.high = 1.5; }), "high: must be in [0, 1] (got 1.5)");
    EXPECT_EQ(with([&](Example& e) { e.high = inf; }), "high: must be in [0, 1] (got inf)");
    EXPECT_EQ(with([](Example& e) { e.count = 0; }), "count: must be in [1, 1000] (got 0)");
    EXPECT_EQ(with([](Example& e) { e.count = 1001; }), "count: must be in [1, 1000] (got 1001)");
    EXPECT_EQ(with([](Example& e) { e.count = 1000000; }),
              "count: must be in [1, 1000] (got 1000000)");  // an int printed as one
    EXPECT_EQ(with([](Example& e) { e.spacing = 1.0; }), "spacing: must be > 1 (got 1)");
    EXPECT_EQ(with([](Example& e) { e.factor = 2; }), "");
    EXPECT_EQ(with([](Example& e) { e.factor = 1; }), "factor: must be 0 or in [2, 16] (got 1)");
    EXPECT_EQ(with([](Example& e) { e.factor = 17; }), "factor: must be 0 or in [2, 16] (got 17)");
    EXPECT_EQ(with([](Example& e) { e.mode = "slow"; }), "");
    EXPECT_EQ(with([](Example& e) { e.mode = "quick"; }),
              "mode: must be fast, slow or off (got 'quick')");
    EXPECT_EQ(with([](Example& e) { e.offsets.clear(); }), "offsets: must hold at least one value");
    EXPECT_EQ(with([](Example& e) { e.flag = false; }), "");
    EXPECT_EQ(with([](Example& e) { e.label.clear(); }), "");
}

TEST(ConfigCheck, RulesAcrossFieldsComeAfterTheFieldRules) {
    Example c;
    c.low = 3.0;
    EXPECT_EQ(problem_of(c), "high: must exceed low");
    c.count = 0;  // a field rule broken too: it is named first
    EXPECT_EQ(problem_of(c), "count: must be in [1, 1000] (got 0)");
}

TEST(ConfigCheck, FirstProblemOnlyAndPartsUnderTheirPrefix) {
    ConfigChecker k;
    k.require(true, "a", "never");
    EXPECT_FALSE(k.problem());
    k.include(std::nullopt, "part.");
    EXPECT_FALSE(k.problem());
    k.include(ConfigProblem{"rings", "must be in [1, 1000] (got 0)"}, "scan_context.");
    k.require(false, "b", "later");
    ASSERT_TRUE(k.problem());
    EXPECT_EQ(k.problem()->key, "scan_context.rings");
    EXPECT_EQ(k.problem()->problem, "must be in [1, 1000] (got 0)");
}

TEST(ConfigCheck, ConfigErrorIsOneLineWithOrWithoutTheFile) {
    const ConfigError in_code("odometry", ConfigProblem{"voxel_size", "must be > 0 (got -1)"});
    EXPECT_STREQ(in_code.what(), "odometry.voxel_size: must be > 0 (got -1)");
    EXPECT_EQ(in_code.key(), "odometry.voxel_size");
    EXPECT_EQ(in_code.problem(), "must be > 0 (got -1)");
    EXPECT_EQ(in_code.file(), "");
    const ConfigError from_file("a.yaml", 4, "odometry.voxel_size", "must be > 0 (got -1)");
    EXPECT_STREQ(from_file.what(), "a.yaml:4: odometry.voxel_size: must be > 0 (got -1)");
    EXPECT_EQ(from_file.file(), "a.yaml");
    EXPECT_EQ(from_file.line(), 4);
    EXPECT_NO_THROW(throw_if(std::nullopt, "odometry"));
    try {
        throw_if(ConfigProblem{"threads", "must be >= 1 (got 0)"}, "odometry");
        ADD_FAILURE() << "no exception";
    } catch (const std::invalid_argument& e) {  // a ConfigError is an invalid_argument
        EXPECT_STREQ(e.what(), "odometry.threads: must be >= 1 (got 0)");
    }
}

}  // namespace
}  // namespace ltm::common
