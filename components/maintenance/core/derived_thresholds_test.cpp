// The time-dependent thresholds: unset ones follow the session's span and views, capped at the
// long-session values; explicit ones are kept as given.
#include "maintenance/core/derived_thresholds.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace ltm::maintenance {
namespace {

TEST(DerivedThresholds, AOneSecondWindowShrinksThem) {
    const MaintenanceConfig c = resolve_thresholds(MaintenanceConfig{}, SessionSeen{1.0, 10});
    EXPECT_DOUBLE_EQ(*c.view_spacing, 0.02);
    EXPECT_DOUBLE_EQ(*c.change.sigma, 0.1);
    EXPECT_DOUBLE_EQ(*c.change.static_span, 0.25);
    EXPECT_EQ(*c.change.min_views, 3);
    EXPECT_DOUBLE_EQ(*c.change.free_dominant, 0.6);
    EXPECT_DOUBLE_EQ(*c.change.changed_score, 0.2);
}

TEST(DerivedThresholds, ALongSessionGetsTheLongSessionValues) {
    for (const double span : {60.0, 250.0, 1e5}) {
        const MaintenanceConfig c =
            resolve_thresholds(MaintenanceConfig{}, SessionSeen{span, std::size_t(span * 5)});
        EXPECT_DOUBLE_EQ(*c.view_spacing, kLongSession.view_spacing) << span;
        EXPECT_DOUBLE_EQ(*c.change.sigma, kLongSession.sigma) << span;
        EXPECT_DOUBLE_EQ(*c.change.static_span, kLongSession.static_span) << span;
        EXPECT_EQ(*c.change.min_views, kLongSession.min_views) << span;
        EXPECT_DOUBLE_EQ(*c.change.free_dominant, kLongSession.free_dominant) << span;
        EXPECT_DOUBLE_EQ(*c.change.changed_score, kLongSession.changed_score) << span;
    }
}

TEST(DerivedThresholds, TheyGrowWithTheSpanUpToTheirCaps) {
    double last_sigma = -1.0, last_span = -1.0, last_spacing = -1.0;
    int last_views = 0;
    for (double t = 0.0; t <= 100.0; t += 0.5) {
        const MaintenanceConfig c =
            resolve_thresholds(MaintenanceConfig{}, SessionSeen{t, std::size_t(t * 10)});
        EXPECT_GE(*c.change.sigma, last_sigma);
        EXPECT_GE(*c.change.static_span, last_span);
        EXPECT_GE(*c.view_spacing, last_spacing);
        EXPECT_GE(*c.change.min_views, last_views);
        EXPECT_GE(*c.change.min_views, 2);
        EXPECT_LE(*c.change.sigma, kLongSession.sigma);
        EXPECT_LE(*c.change.static_span, kLongSession.static_span);
        last_sigma = *c.change.sigma;
        last_span = *c.change.static_span;
        last_spacing = *c.view_spacing;
        last_views = *c.change.min_views;
    }
}

TEST(DerivedThresholds, ExplicitKeysWin) {
    MaintenanceConfig given;
    given.view_spacing = 0.5;
    given.change.sigma = 2.0;
    given.change.static_span = 7.0;
    given.change.min_views = 9;
    given.change.free_dominant = 0.8;
    given.change.changed_score = 0.5;
    for (const double span : {0.5, 1000.0}) {
        const MaintenanceConfig c = resolve_thresholds(given, SessionSeen{span, 5});
        EXPECT_DOUBLE_EQ(*c.view_spacing, 0.5);
        EXPECT_DOUBLE_EQ(view_spacing_at(given, span), 0.5);
        EXPECT_DOUBLE_EQ(*c.change.sigma, 2.0);
        EXPECT_DOUBLE_EQ(*c.change.static_span, 7.0);
        EXPECT_EQ(*c.change.min_views, 9);
        EXPECT_DOUBLE_EQ(*c.change.free_dominant, 0.8);
        EXPECT_DOUBLE_EQ(*c.change.changed_score, 0.5);
    }
}

TEST(DerivedThresholds, AnOddSpanIsAnEmptyOne) {
    for (const double span : {-5.0, std::numeric_limits<double>::quiet_NaN(),
                              std::numeric_limits<double>::infinity()}) {
        const MaintenanceConfig c = resolve_thresholds(MaintenanceConfig{}, SessionSeen{span, 0});
        EXPECT_DOUBLE_EQ(*c.change.sigma, 0.0) << span;
        EXPECT_DOUBLE_EQ(*c.change.static_span, 0.0) << span;
        EXPECT_EQ(*c.change.min_views, 2) << span;
        EXPECT_DOUBLE_EQ(view_spacing_at(MaintenanceConfig{}, span), 0.0) << span;
    }
}

}  // namespace
}  // namespace ltm::maintenance
