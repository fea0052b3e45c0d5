// The translation search around a pose (translation_search.hpp) on a synthetic scene's map.
#include "localisation/core/translation_search.hpp"

#include <gtest/gtest.h>

#include "localisation/core/global_localiser.hpp"
#include "localisation/core/localiser_test_scene.hpp"

namespace ltm::localisation {
namespace {

using namespace test_scene;

TEST(TranslationSearch, FindsTheOffsetOfAPoseMetresOffWhereTheStructureFits) {
    const SceneMap& s = scene_map();
    const Eigen::Isometry3d truth = mt::xy_yaw(1.0, 0.5, 12.0);
    const std::vector<Eigen::Vector3f> scan = mt::view(s.scene, truth, 60.0);
    const registration::ImlsParams imls;
    TranslationSearchConfig config;
    for (const auto& [dx, dy] : {std::pair{3.0, -2.0}, std::pair{-4.0, 1.0}, std::pair{0.0, 5.0}}) {
        Eigen::Isometry3d start = truth;
        start.translation() += Eigen::Vector3d(dx, dy, 0.0);
        const TranslationSearchResult r =
            search_translation(scan, s.map->target().fine, imls, start, config);
        EXPECT_LT(error_of(r.T_map_lidar, truth).translation, 0.75) << dx << " " << dy;
        EXPECT_NEAR(r.offset, std::hypot(dx, dy), 0.75);
        EXPECT_GT(r.share, r.share_at_start + 0.2) << "structure on surfaces at the truth only";
    }
    // At the truth itself: no offset fits better.
    const TranslationSearchResult at =
        search_translation(scan, s.map->target().fine, imls, truth, config);
    EXPECT_EQ(at.offset, 0.0);
    EXPECT_LT(error_of(at.T_map_lidar, truth).translation, 1e-9);
    // Beyond the radius: not found (no search at all with radius 0).
    Eigen::Isometry3d far = truth;
    far.translation() += Eigen::Vector3d(8.0, 0.0, 0.0);
    config.radius = 0.0;
    const TranslationSearchResult none =
        search_translation(scan, s.map->target().fine, imls, far, config);
    EXPECT_EQ(none.offset, 0.0);
    EXPECT_LT(error_of(none.T_map_lidar, far).translation, 1e-9);
}

TEST(TranslationSearch, TurnsAGuessThatIsDegreesOffAsWellAsMetres) {
    const SceneMap& s = scene_map();
    const Eigen::Isometry3d truth = mt::xy_yaw(-3.0, -0.6, 25.0);
    const std::vector<Eigen::Vector3f> scan = mt::view(s.scene, truth, 60.0);
    const registration::ImlsParams imls;
    // 3 m off and turned 3 deg about the LiDAR.
    Eigen::Isometry3d start = truth;
    start.linear() = Eigen::AngleAxisd(3.0 * kDeg, Eigen::Vector3d::UnitZ()) * truth.linear();
    start.translation() += Eigen::Vector3d(2.0, -2.0, 0.0);
    TranslationSearchConfig config;  // no yaws: the offset alone, the rotation stays 3 deg off
    const TranslationSearchResult plain =
        search_translation(scan, s.map->target().fine, imls, start, config);
    EXPECT_EQ(plain.yaw, 0.0);
    EXPECT_NEAR(error_of(plain.T_map_lidar, truth).rotation_deg, 3.0, 1e-6);
    config.yaw_offsets = {-3.0, 0.0, 3.0};
    const TranslationSearchResult r =
        search_translation(scan, s.map->target().fine, imls, start, config);
    EXPECT_EQ(r.yaw, -3.0);
    EXPECT_LT(error_of(r.T_map_lidar, truth).rotation_deg, 0.01);
    EXPECT_LT(error_of(r.T_map_lidar, truth).translation, 0.75);
    EXPECT_GT(r.share, plain.share);
}

TEST(TranslationSearch, ItsKeysAreCheckedWithTheGlobalLocalisers) {
    GlobalLocaliserConfig c;
    EXPECT_FALSE(validate(c));
    c.search.step = 0.0;
    ASSERT_TRUE(validate(c));
    EXPECT_EQ(validate(c)->key, "search.step");
    c = GlobalLocaliserConfig();
    c.search.below_inlier_fraction = 1.5;
    EXPECT_EQ(validate(c)->key, "search.below_inlier_fraction");
    c = GlobalLocaliserConfig();
    EXPECT_EQ(c.search.yaw_offsets.size(), 3u);  // the global localiser's: -3, 0, 3 deg
    c.search.yaw_offsets.clear();
    EXPECT_EQ(validate(c)->key, "search.yaw_offsets");
}

}  // namespace
}  // namespace ltm::localisation
