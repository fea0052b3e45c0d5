#pragma once
// A keyframe digested where it is made (on the robot), for a Mapper elsewhere (the base station,
// over a narrow link): its two descriptors made from the whole scan, and only the points a loop
// verification registers (LoopVerifier's sample: the first point of each cell of a
// verification.downsample grid, at most verification.max_points of them taken evenly). The
// verifier samples the sample again and gets the same points (the grid keeps one point a cell,
// in order), so a Mapper given a digested keyframe decides exactly as one given the whole scan:
// the same loops, the same map.
// A descriptor is used only when it was made with the Mapper's own settings (made_alike);
// otherwise the Mapper makes it again from the points it has.
#include <Eigen/Core>
#include <vector>

#include "mapping/core/mapper_config.hpp"
#include "places/core/scan_context.hpp"
#include "registration/core/preprocess.hpp"

namespace ltm::mapping {

// A descriptor and the settings that made it (empty: none).
struct MadeDescriptor {
    places::ScanContext descriptor;
    places::ScanContextConfig made_with;
};

// What a keyframe may bring besides its points.
struct KeyframeDescriptors {
    MadeDescriptor loop;          // MapperConfig::scan_context's kind
    MadeDescriptor localisation;  // MapperConfig::localisation_descriptor's kind
};

// The same descriptor from the same points: kind, rings, sectors, ranges and sensor height (as the
// 32-bit floats a message carries them in) agree. The comparison settings (empty_bin_cost,
// shift_search_radius) do not make the descriptor.
bool made_alike(const places::ScanContextConfig& a, const places::ScanContextConfig& b);

// `given` when it is not empty, was made as `config` makes it and has the shape it says; else
// nullptr.
const places::ScanContext* usable(const MadeDescriptor& given,
                                  const places::ScanContextConfig& config);

class KeyframeDigester {
  public:
    // The descriptor settings and the verification's sample of `config` (the base station's
    // mapping configuration). Throws common::ConfigError as Mapper does.
    explicit KeyframeDigester(const MapperConfig& config);

    // Descriptors from `points` (the whole down-sampled scan, LiDAR frame) and the sample the
    // verification registers, in `sampled` (may not alias `points`).
    void digest(const std::vector<Eigen::Vector3f>& points, KeyframeDescriptors* descriptors,
                std::vector<Eigen::Vector3f>* sampled);

  private:
    MapperConfig config_;
    registration::VoxelDownsampler sampler_;
};

}  // namespace ltm::mapping
