#include "mapping/params/mapper_params.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>
#include <map>
#include <set>
#include <sstream>

namespace ltm::mapping {
namespace {

runtime::Parameters params_of(const std::string& yaml) {
    return runtime::Parameters(YAML::Load(yaml), "test.yaml", "mapping");
}

std::string error_of(const std::string& yaml) {
    try {
        runtime::Parameters p = params_of(yaml);
        load_mapper_config(p);
        p.check_all_used();
    } catch (const runtime::ConfigError& e) {
        return e.what();
    }
    return "";
}

TEST(MapperParams, PresetThenOverrides) {
    runtime::Parameters p = params_of(
        "preset: narrow\nscan_context: {kind: mean_variance, rings: 24}\n"
        "verification: {fine: {max_iterations: 70}, yaw_offsets: [-10, 0, 10]}\n"
        "pose_graph: {loop_loss: huber}\nloop_cooldown_keyframes: 0\n"
        "localisation_descriptor: {sectors: 90, min_range: 1.5}\n");
    const MapperConfig c = load_mapper_config(p);
    EXPECT_NO_THROW(p.check_all_used());
    const MapperConfig narrow = mapper_preset(common::SensorPreset::kNarrow);
    EXPECT_EQ(c.scan_context.kind, places::ScanContextKind::kMeanVariance);
    EXPECT_EQ(c.scan_context.rings, 24);
    EXPECT_EQ(c.verification.fine.max_iterations, 70);
    EXPECT_EQ(c.verification.yaw_offsets, (std::vector<double>{-10, 0, 10}));
    EXPECT_EQ(c.pose_graph.loop_loss, "huber");
    EXPECT_EQ(c.loop_cooldown_keyframes, 0);
    EXPECT_EQ(c.localisation_descriptor.sectors, 90);
    EXPECT_EQ(c.localisation_descriptor.min_range, 1.5);
    // The localisation descriptor: ScanContext++ over the preset's descriptor range.
    EXPECT_EQ(c.localisation_descriptor.kind, places::ScanContextKind::kMeanVariance);
    EXPECT_EQ(c.localisation_descriptor.rings, 20);
    EXPECT_DOUBLE_EQ(c.localisation_descriptor.max_range, narrow.scan_context.max_range);
    EXPECT_DOUBLE_EQ(c.localisation_descriptor.sensor_height, narrow.scan_context.sensor_height);
    // Untouched keys: the preset's.
    EXPECT_DOUBLE_EQ(c.scan_context.max_range, narrow.scan_context.max_range);
    EXPECT_EQ(c.verification.min_inliers, narrow.verification.min_inliers);
    EXPECT_EQ(c.verification.coarse.max_iterations, narrow.verification.coarse.max_iterations);
    // Nothing given: the default preset.
    runtime::Parameters empty(YAML::Node(), "test.yaml", "mapping");
    const MapperConfig d = load_mapper_config(empty);
    EXPECT_DOUBLE_EQ(d.scan_context.sensor_height,
                     mapper_preset(common::SensorPreset::kHdl64).scan_context.sensor_height);
    EXPECT_EQ(d.scan_context.kind, places::ScanContextKind::kMaxHeight);
}

void merge(YAML::Node dst, const YAML::Node& src) {
    for (const auto& kv : src) {
        const std::string k = kv.first.as<std::string>();
        if (dst[k].IsMap() && kv.second.IsMap()) {
            merge(dst[k], kv.second);
        } else {
            dst[k] = kv.second;
        }
    }
}

TEST(MapperParams, EveryFieldIsReadByItsOwnKey) {
    // Give every visited key a distinct value in a nested YAML map, load it, and find each value
    // in the field of that key: a key read into a wrong field, or two fields sharing a key, fails.
    MapperConfig expected;
    YAML::Node root(YAML::NodeType::Map);  // not a default Node: copies of that do not share
    std::set<std::string> keys;
    int counter = 0;
    visit_fields(expected, [&](const std::string& key, auto& field, const auto&) {
        using T = std::decay_t<decltype(field)>;
        EXPECT_TRUE(keys.insert(key).second) << "key visited twice: " << key;
        ++counter;
        if constexpr (std::is_same_v<T, bool>) {
            field = !field;
        } else if constexpr (std::is_same_v<T, std::string>) {
            field = "huber";
        } else if constexpr (std::is_same_v<T, std::vector<double>>) {
            field = {double(counter), double(counter + 1)};
        } else {
            field = static_cast<T>(1000 + counter);
        }
        YAML::Node node;
        node = field;
        for (std::size_t dot = key.rfind('.'), end = key.size(); end != 0;
             end = dot, dot = key.rfind('.', dot - 1)) {
            const std::size_t start = dot == std::string::npos ? 0 : dot + 1;
            YAML::Node parent;
            parent[key.substr(start, end - start)] = node;
            node = parent;
            if (dot == std::string::npos) break;
        }
        merge(root, node);
    });
    EXPECT_GT(counter, 60);
    runtime::Parameters p(root, "test.yaml", "mapping");
    MapperConfig read;
    visit_fields(
        read, [&](const std::string& key, auto& field, const auto&) { field = p.get(key, field); });
    EXPECT_NO_THROW(p.check_all_used());
    std::map<std::string, std::string> want, got;
    auto text = [](const auto& v) {
        std::ostringstream s;
        if constexpr (std::is_same_v<std::decay_t<decltype(v)>, std::vector<double>>) {
            for (double x : v) s << x << ' ';
        } else {
            s << v;
        }
        return s.str();
    };
    visit_fields(expected, [&](const std::string& key, auto& field, const auto&) {
        want[key] = text(field);
    });
    visit_fields(read,
                 [&](const std::string& key, auto& field, const auto&) { got[key] = text(field); });
    EXPECT_EQ(want, got);
}

TEST(MapperParams, RejectsWhatItDoesNotKnowNamingFileLineAndKey) {
    EXPECT_EQ(error_of("preset: vlp32\nscan_context: {rigns: 30}")
                  .rfind("test.yaml:2: mapping.scan_context.rigns: unknown parameter", 0),
              0u);
    EXPECT_EQ(
        error_of("localisation_descriptor: {rigns: 30}")
            .rfind("test.yaml:1: mapping.localisation_descriptor.rigns: unknown parameter", 0),
        0u)
        << error_of("localisation_descriptor: {rigns: 30}");
    // Always ScanContext++: the kind is not a parameter.
    EXPECT_EQ(error_of("localisation_descriptor: {kind: max_height}")
                  .rfind("test.yaml:1: mapping.localisation_descriptor.kind: unknown parameter", 0),
              0u);
    EXPECT_EQ(error_of("localisation_descriptor: {max_range: 30, min_range: 40}"),
              "test.yaml:1: mapping.localisation_descriptor.min_range: must be smaller than "
              "max_range");
    EXPECT_EQ(error_of("loop_detection: {max_distance: far}"),
              "test.yaml:1: mapping.loop_detection.max_distance: expected a number, got 'far'");
    EXPECT_NE(error_of("a: 1\nscan_context: {sectors: 0}")
                  .find("test.yaml:2: mapping.scan_context.sectors:"),
              std::string::npos)
        << error_of("a: 1\nscan_context: {sectors: 0}");
    EXPECT_NE(error_of("pose_graph:\n  loop_loss: tukey")
                  .find("test.yaml:2: mapping.pose_graph.loop_loss:"),
              std::string::npos)
        << error_of("pose_graph:\n  loop_loss: tukey");
    EXPECT_NE(error_of("preset: hdl32")
                  .find("test.yaml:1: mapping.preset: unknown sensor preset 'hdl32'"),
              std::string::npos)
        << error_of("preset: hdl32");
    EXPECT_EQ(error_of("scan_context: {kind: fancy}"),
              "test.yaml:1: mapping.scan_context.kind: expected max_height (Scan Context) or "
              "mean_variance "
              "(ScanContext++), got 'fancy'");
    EXPECT_NE(error_of("max_loops_per_keyframe: 0")
                  .find("test.yaml:1: mapping.max_loops_per_keyframe: must be >= 1"),
              std::string::npos)
        << error_of("max_loops_per_keyframe: 0");
}

TEST(MapperParams, EachKindOfRuleFromYamlNamesFileLineAndKey) {
    EXPECT_EQ(error_of("a: 1\nscan_context: {sectors: 2}"),
              "test.yaml:2: mapping.scan_context.sectors: must be in [4, 3600] (got 2)");
    EXPECT_EQ(error_of("scan_context:\n  max_range: 30\n  min_range: 40"),
              "test.yaml:3: mapping.scan_context.min_range: must be smaller than max_range");
    EXPECT_EQ(error_of("verification:\n  yaw_offsets: []"),
              "test.yaml:2: mapping.verification.yaw_offsets: must hold at least one value");
    EXPECT_EQ(
        error_of("verification:\n  coarse:\n    min_normal_agreement: 2"),
        "test.yaml:3: mapping.verification.coarse.min_normal_agreement: must be in [0, 1] (got 2)");
    EXPECT_EQ(error_of("verification: {coarse_factor: 1}"),
              "test.yaml:1: mapping.verification.coarse_factor: must be 0 or in [2, 16] (got 1)");
    EXPECT_EQ(
        error_of("pose_graph: {loop_loss: tukey}"),
        "test.yaml:1: mapping.pose_graph.loop_loss: must be cauchy, huber or none (got 'tukey')");
    EXPECT_EQ(error_of("odometry_edge: {sigma_rotation: .nan}"),
              "test.yaml:1: mapping.odometry_edge.sigma_rotation: must be > 0 (got nan)");
    EXPECT_EQ(error_of("loop_edge: {sigma_translation: .inf}"),
              "test.yaml:1: mapping.loop_edge.sigma_translation: must be > 0 (got inf)");
    // A limit that may be infinite (no limit): accepted as before.
    EXPECT_EQ(error_of("loop_detection: {exclude_recent_seconds: .inf}\n"
                       "pose_graph: {outlier_translation: .inf}"),
              "");
}

TEST(MapperParams, FileWithOrWithoutTheMappingSection) {
    const std::string path =
        ::testing::TempDir() + "/mapper_params_" + std::to_string(::getpid()) + ".yaml";
    { std::ofstream(path) << "mapping:\n  loop_edge: {sigma_translation: 0.2}\n"; }
    EXPECT_DOUBLE_EQ(load_mapper_config_file(path, "vlp16").loop_edge.sigma_translation, 0.2);
    {
        std::ofstream(path)
            << "preset: narrow\nloop_edge: {sigma_rotation: 1.0}\nodometry: {voxel_size: 1}\n";
    }
    try {
        load_mapper_config_file(path);
        ADD_FAILURE() << "an odometry key in a mapping file must be refused";
    } catch (const runtime::ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find(":3: mapping.odometry.voxel_size: unknown parameter"),
                  std::string::npos)
            << e.what();
    }
    EXPECT_THROW(load_mapper_config_file(path, "vlp32"), runtime::ConfigError);  // preset twice
    std::remove(path.c_str());
}

// `preset: auto` (the mapping component's default): the spinning sensors' settings, the same as
// every spinning preset's (the mapping sees keyframes, not scans).
TEST(MapperParams, AutoIsEverySpinningPresetsSettings) {
    runtime::Parameters p = params_of("preset: auto\n");
    const MapperConfig c = load_mapper_config(p);
    for (const common::SensorPreset s :
         {common::SensorPreset::kHdl64, common::SensorPreset::kVlp32, common::SensorPreset::kVlp16,
          common::SensorPreset::kOs1_64}) {
        const MapperConfig m = mapper_preset(s);
        EXPECT_EQ(c.scan_context.max_range, m.scan_context.max_range);
        EXPECT_EQ(c.scan_context.sensor_height, m.scan_context.sensor_height);
        EXPECT_EQ(c.loop_detection.max_distance, m.loop_detection.max_distance);
        EXPECT_EQ(c.verification.min_inliers, m.verification.min_inliers);
        EXPECT_EQ(c.long_term.keyframe_angle, m.long_term.keyframe_angle);
    }
    EXPECT_NE(c.verification.min_inliers,
              mapper_preset(common::SensorPreset::kNarrow).verification.min_inliers);
    EXPECT_NE(error_of("preset: vlp64\n").find("or auto"), std::string::npos);
}

}  // namespace
}  // namespace ltm::mapping
