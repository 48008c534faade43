#pragma once
// Sea-state builder: a directional frequency spectrum S(w) D(theta; w) -> the list of linear
// wave components that drives BOTH the Boussinesq wave maker and the deep-water FFT field
// (issue 5, coherence), so the harbour and the open sea show the same waves.
//
// Amplitudes by the integral rule (seed 001 eq. 16-17): the (w, theta) plane is cut into cells
// and each component carries exactly the variance of its cell,
//   a_ij = sqrt(2 * integral over cell ij of S(w) D(theta; w) dw dtheta),
// so the cells tile the kept band and sum a^2/2 = the band's variance whatever the number of
// components: changing the resolution changes no wave height.
//
// Exact looping: with a loop period T > 0 every component frequency is a whole multiple of
// 2 pi / T and the cells are cut around those harmonics, so eta(x, t + T) = eta(x, t).
//
// Phases: uniform in [0, 2 pi) from std::mt19937_64 seeded with `seed`, one draw per component in
// the order of the output (frequency-major, then direction), mapped from the raw 64-bit draws (not
// std::uniform_real_distribution, whose output differs between standard libraries), so the same
// seed gives the same sea on every platform.
#include <cstdint>
#include <memory>

#include "nearshore/ocean/spectrum.hpp"
#include "nearshore/ocean/wave_component.hpp"

namespace nearshore::ocean {

struct DirectionalSeaSpecification {
  std::shared_ptr<const FrequencySpectrum> spectrum;      ///< required
  std::shared_ptr<const DirectionalSpreading> spreading;  ///< required (its mean direction is used)
  int frequency_count = 64;   ///< number of frequency cells (>= 1)
  int direction_count = 16;   ///< number of direction cells (1 = long-crested, all energy on the mean direction)
  /// Frequency band (rad/s). 0 = automatic: the band holding `kept_variance_fraction` of m0,
  /// with one fifth of the rest cut below the band and four fifths above (the long tail).
  double min_frequency_rad_s = 0.0;
  double max_frequency_rad_s = 0.0;
  double kept_variance_fraction = 0.995;  ///< of the frequency spectrum, for the automatic band
  /// Half-width of the direction band around the mean (rad). 0 = automatic: the half-width that
  /// holds 99.9 % of D at the peak frequency.
  double direction_half_width_rad = 0.0;
  double loop_period_s = 0.0;  ///< T_loop (s); 0 = no exact periodicity
  std::uint64_t seed = 1;      ///< phases; recorded in SeaState::seed
};

/// Discretises the specification (see the top of this file). Throws nearshore::Error naming the
/// field at fault for a missing spectrum/spreading, counts < 1, an empty band, or a loop period
/// too short to give every frequency cell its own harmonic of 2 pi / T.
SeaState build_sea_state(const DirectionalSeaSpecification& specification);

/// A single regular wave of height H (m, crest to trough) and period T (s) travelling in
/// `direction_rad`; its loop period is T and its seed 0.
SeaState regular_wave_sea_state(double height_m, double period_s, double direction_rad, double phase_rad = 0.0);

/// Hs = 4 sqrt(sum a_i^2 / 2) (m): the significant wave height the components carry.
double significant_wave_height_m(const SeaState& sea_state);

/// The random phase in [0, 2 pi) made from one raw 64-bit draw (53 high bits).
double phase_from_draw_rad(std::uint64_t draw);

}  // namespace nearshore::ocean
