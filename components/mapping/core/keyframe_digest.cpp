#include "mapping/core/keyframe_digest.hpp"

#include "common/core/config_check.hpp"

namespace ltm::mapping {

bool made_alike(const places::ScanContextConfig& a, const places::ScanContextConfig& b) {
    return a.kind == b.kind && a.rings == b.rings && a.sectors == b.sectors &&
           float(a.max_range) == float(b.max_range) && float(a.min_range) == float(b.min_range) &&
           float(a.sensor_height) == float(b.sensor_height);
}

const places::ScanContext* usable(const MadeDescriptor& given,
                                  const places::ScanContextConfig& config) {
    const places::ScanContext& d = given.descriptor;
    if (d.empty() || !made_alike(given.made_with, config)) return nullptr;
    const std::size_t bins = std::size_t(config.rings) * std::size_t(config.sectors);
    const bool spread = d.kind == places::ScanContextKind::kMeanVariance;
    if (d.kind != config.kind || d.rings != config.rings || d.sectors != config.sectors ||
        d.value.size() != bins || d.occupied.size() != bins ||
        d.spread.size() != (spread ? bins : 0)) {
        return nullptr;
    }
    return &d;
}

KeyframeDigester::KeyframeDigester(const MapperConfig& config) : config_(config) {
    common::throw_if(validate(config_), "mapping");
}

void KeyframeDigester::digest(const std::vector<Eigen::Vector3f>& points,
                              KeyframeDescriptors* descriptors,
                              std::vector<Eigen::Vector3f>* sampled) {
    descriptors->loop = {places::make_scan_context(points, config_.scan_context),
                         config_.scan_context};
    descriptors->localisation = {places::make_scan_context(points, config_.localisation_descriptor),
                                 config_.localisation_descriptor};
    const registration::LoopVerifierConfig& v = config_.verification;
    sampler_.sample(points, v.downsample, std::size_t(v.max_points), sampled);
}

}  // namespace ltm::mapping
