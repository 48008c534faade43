#pragma once
// What a bake records of its deep-water field for the runtime (docs/deep-water.md "Output"): the
// manifest's typed deep_water section and the coefficient files beside the frames, both defined by
// sequence/deep_water_section.hpp; the field itself is ocean/deep_water.hpp.
#include <filesystem>

#include "nearshore/ocean/deep_water.hpp"
#include "nearshore/sequence/deep_water_section.hpp"

namespace nearshore::bake {

/// The field's description: spectrum, depth, T_loop, seed, choppiness, foam threshold, each
/// cascade's band and variance, the unresolved slope variance. No coefficient files, coupling or
/// tile set yet.
sequence::DeepWaterSection describe_deep_water_field(const ocean::DeepWaterField& field);

/// Writes deep_water_cascade_<i>.bin for every cascade into `folder` (atomically) and records each
/// file (size, XXH64) in section.cascades[i].coefficients.
void write_deep_water_coefficient_files(const ocean::DeepWaterField& field, const std::filesystem::path& folder,
                                        sequence::DeepWaterSection& section);

}  // namespace nearshore::bake
