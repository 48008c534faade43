#pragma once
// Synthetic sequences with known answers, for tests, benchmarks and the compression table until a
// real bake exists: a linear (Airy) sea of plane-wave components over constant depth, with the
// depth-integrated fluxes that belong to it, and a random walk with a planted repeat.
#include <cstdint>
#include <filesystem>
#include <vector>

#include "nearshore/ocean/wave_component.hpp"
#include "nearshore/sequence/sequence_writer.hpp"

namespace nearshore::loops {

struct SyntheticSea {
  double still_water_depth_m = 10;
  std::vector<ocean::LatticeWave> components;  ///< eta = a cos(kx x + ky y - omega t + phase)
};

/// omega from linear dispersion omega^2 = g k tanh(k d) (Airy).
double linear_dispersion_omega_rad_s(double wavenumber_rad_m, double depth_m);

/// A sea whose components all have periods dividing `period_s` exactly (harmonics n = 1..count of
/// 2 pi / period_s), so every frame repeats after period_s: the "known common period" case.
/// Directions and phases from `seed`; wavenumbers from the dispersion relation.
SyntheticSea periodic_sea(double period_s, int component_count, double significant_height_m, double depth_m,
                          std::uint64_t seed);
/// An irregular sea: `component_count` components with JONSWAP (ocean/spectrum.hpp; peak period
/// `peak_period_s`, gamma 3.3) amplitudes, spread +-40 degrees about `mean_direction_rad`, random phases and
/// incommensurate frequencies, so it never repeats exactly.
SyntheticSea irregular_sea(double peak_period_s, int component_count, double significant_height_m, double depth_m,
                           double mean_direction_rad, std::uint64_t seed);

/// Fills eta (m) and the depth-integrated linear fluxes P, Q (m^2/s) at time t; for each component
/// the flux is (omega / k) * k_hat * eta_component (linear theory, integrated over the depth).
void evaluate_sea(const SyntheticSea& sea, const GridGeometry& geometry, double time_s, Raster<float>& eta,
                  Raster<float>& flux_x, Raster<float>& flux_y);

/// Writes `frame_count` frames of the sea into a sequence folder (open water of the sea's depth).
void write_sea_sequence(const std::filesystem::path& folder, const SyntheticSea& sea, const GridGeometry& geometry,
                        int frame_count, double frame_interval_s, double loop_period_s,
                        sequence::FrameEncoding encoding = {});

/// A random walk of fields, f(k+1) = f(k) + white noise of `step_rms_m` per cell, in which frames
/// [repeat_source, repeat_source + repeat_length) are copied to [repeat_copy, repeat_copy + repeat_length):
/// the only exact repeat, whose loop the tables must find. Float frames (exact copies on disk).
void write_planted_repeat_sequence(const std::filesystem::path& folder, const GridGeometry& geometry,
                                   int frame_count, int repeat_source, int repeat_copy, int repeat_length,
                                   double step_rms_m, std::uint64_t seed);

}  // namespace nearshore::loops
