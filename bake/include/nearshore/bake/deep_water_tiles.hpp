#pragma once
// The optional baked deep-water tile set (issue 5), for engines that cannot run an FFT: one
// cascade of the field written as a baked sequence (sequence/sequence_writer.hpp, the same
// format as the harbour bake), one frame per frame interval over one loop:
//   surface_elevation  eta (m)
//   flux_x, flux_y     depth-integrated linear velocity P, Q (m^2/s) = sum a (w/k) k^ cos(...)
//   breaking           f_b of this cascade's own Jacobian (seed 000 eq. 3.45, J_b = kStokesBreakingJacobian)
// The grid is the cascade's N x N lattice (cell centres on the FFT nodes: origin -L/(2N)), over
// open water of the field's depth (1000 m when deep). The tile repeats with period L in x and y.
// The choppy displacement is not stored: the format has no channel for it; engines that want it
// run the FFT from the coefficients instead (DeepWaterField::write_coefficients).
#include <filesystem>

#include "nearshore/ocean/deep_water.hpp"
#include "nearshore/sequence/sequence_format.hpp"

namespace nearshore::bake {

struct TileSetSummary {
  int frame_count = 0;
  double frame_interval_s = 0.0;
  std::uintmax_t bytes = 0;        ///< all files of the folder
  std::uintmax_t frame_bytes = 0;  ///< the frame files alone
};

/// Writes cascade `cascade` of `field` over one loop (the field must loop: T_loop > 0) with
/// `frames_per_loop` frames into `folder`; the manifest's deep_water entry is field.description().
/// frame_limit > 0 writes only the first frame_limit frames, as a sample (e.g. to measure the
/// bytes per frame): that sequence is then not a loop (loop_period_s = 0 in its manifest).
/// Throws nearshore::Error for a field that does not loop or a bad cascade index.
TileSetSummary write_deep_water_tile_set(ocean::DeepWaterField& field, int cascade, int frames_per_loop,
                                         const std::filesystem::path& folder,
                                         const sequence::FrameEncoding& encoding = {}, int frame_limit = 0);

}  // namespace nearshore::bake
