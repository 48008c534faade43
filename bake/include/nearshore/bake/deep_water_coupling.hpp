#pragma once
// The deep-water FFT field meets the harbour bake (issue 5, "coherence with the harbour"): the
// Boussinesq wave maker makes the field's own lattice waves, so that inland of the source line the
// baked waves and the field are the same waves to linear order, and the runtime can cross-fade from
// one to the other in a blending zone without a seam (docs/deep-water.md, "Coherence").
//
// Frames. The field's x = 0, y = 0 is the harbour grid's south-west corner (GridGeometry
// origin_x_m, origin_y_m in the projected frame), i.e. the case file's local frame; the field's
// time is the bake's simulated time (frame k at first_frame_time_s + k frame_interval_s). The
// solver works in the projected frame, whose zero may be hundreds of kilometres away (UTM), and
// its source line radiates each component with the model's own wavenumber k_B at the line's depth
// d (the linear Madsen & Sorensen 1992 relation, B = 1/15:
// w^2 = g d k^2 (1 + B (kd)^2) / (1 + (B + 1/3) (kd)^2); docs/solver.md "Wave maker"), its phase
// referred to that zero. A lattice wave eta = a cos(k_L . x - w t + phi) becomes the maker component
//   tangential wavenumber  l      = k_L . t                 (kept along the line: Snell's law
//   normal wavenumber      k_B,n  = sqrt(k_B^2 - l^2)        across the change of dispersion relation)
//   direction              theta' = angle of (k_B,n n + l t)
//   phase                  phi'   = phi + k_L,n s_line - k_B,n S_line - l T_0
// (n, t the inward normal and tangential axes, s_line / S_line the line's local / projected position
// along n, T_0 the grid origin along t, all components signed along the axes), so that on the source
// line, at every point and every time, a cos(k' . X - w t + phi') = a cos(k_L . x - w t + phi) with
// X = x + origin. Amplitude and frequency are the field's own.
//
// Inland the two drift apart: the field keeps k_L,n at the source line's depth, the solver's waves
// follow the discrete model (docs/solver.md "Accuracy": the continuous B = 1/15 relation, the
// spatial sinc of the staggered differences and the Crank-Nicolson phase lag) over the bed inland.
// Per wave, at distance s from the line (WKB along the normal over the mean wet depth of each grid
// line, l kept):
//   w_c          = (2/dt) tan(w dt/2)
//   k_n,disc(s)  = (2/dx) asin((dx/2) sqrt(k_B(w_c, d(s))^2 - ((2/dx) sin(l dx/2))^2))
//   delta(s)     = integral from 0 to s of (k_n,disc - k_L,n) ds'
//   K(s)         = sqrt(c_g0 cos(theta_0) / (c_g(s) cos(theta(s))))   (linear shoaling, refraction)
// and the relative RMS difference of the two is
//   eps(s)^2     = sum a^2 (1 + K^2 - 2 K cos delta) / sum a^2.
#include <limits>
#include <vector>

#include <nlohmann/json.hpp>

#include "nearshore/boussinesq/boussinesq_solver.hpp"
#include "nearshore/ocean/deep_water.hpp"
#include "nearshore/core/harbour_grid.hpp"
#include "nearshore/sequence/deep_water_section.hpp"

namespace nearshore::bake {

/// Which of the field's lattice waves the wave maker makes.
struct WaveMakerBand {
  /// The frequency band (rad/s): the band the grid carries (bake_case: k d <= 3, cells per wavelength).
  double min_frequency_rad_s = 0.0;
  double max_frequency_rad_s = std::numeric_limits<double>::infinity();
  double min_amplitude_ratio = 1e-3;  ///< of the field's largest amplitude: smaller waves are left out
  /// k_B,n / k_B at least this, the cosine of the largest angle to the line's normal: the source
  /// line radiates within 78 degrees of it (boussinesq_source.cpp refuses below 0.2; 0.21 keeps a
  /// margin); 1 keeps only normally incident waves (a flume with side walls).
  double min_normal_fraction = 0.21;
};

/// The seam criterion (docs/deep-water.md): blending (1 - w) F + w B of two sums of the same waves
/// whose relative RMS difference is eps gives the variance sigma^2 (1 - w (1 - w) eps^2), a band of
/// lower waves in mid-zone with Hs ratio sqrt(1 - eps^2 / 4); eps <= 0.28 keeps it above 0.99.
inline constexpr double kSeamlessRelativeRms = 0.28;

/// Where the runtime cross-fades from the FFT field (seaward) to the baked field (inland).
/// Distances are along the wave maker's inward normal, from the source line, metres.
struct BlendingZone {
  boussinesq::Side side = boussinesq::Side::kSouth;  ///< the side the waves come from (the wave maker's `facing`)
  /// The source line's local position (from the SW corner) along x (west/east) or y (south/north).
  double source_line_m = 0.0;
  /// The inland edge of the source strip (its Gaussian < e^-9 beyond): the cross-fade starts here.
  double start_m = 0.0;
  /// One peak wavelength of the maker (model wavenumber), or less (down to half) where eps would pass
  /// kSeamlessRelativeRms within it.
  double width_m = 0.0;
  double predicted_relative_rms_start = 0.0;  ///< eps of the carried waves at start_m (relative_rms_drift)
  double predicted_relative_rms_end = 0.0;    ///< ... at start_m + width_m
  bool seamless = true;                       ///< predicted_relative_rms_end <= kSeamlessRelativeRms

  /// Distance inland of the source line of a local point (m; negative seaward).
  double distance_inland_m(double x_m, double y_m) const;
  /// The baked field's weight w(s) at distance s inland: 0 for s <= start, sin^2(pi/2 (s - start) / width)
  /// inside, 1 beyond; the field shown is (1 - w) FFT + w baked, for eta, P, Q and slopes alike.
  double baked_weight(double distance_inland_m) const;
  /// As recorded in the manifest's deep_water.coupling.blending.
  sequence::DeepWaterBlendingRecord record() const;
};

/// What the solver does to the carried waves inland of the source line (the drift model above).
struct InlandPropagation {
  /// Cell size normal to the source line (the step of depth_m) and along it, metres: dx and dy for
  /// a line facing west or east, dy and dx for one facing south or north (rectangular cells).
  double spacing_m = 1.0, tangential_spacing_m = 1.0;
  double time_step_s = 0.0, dispersion_coefficient = 1.0 / 15.0;
  /// The mean wet depth of the grid line at s = 0, dx, 2 dx, ... inland (to the grid's edge).
  std::vector<double> depth_m;
};

/// The wave maker made of the field's waves.
struct CoupledWaveMaker {
  ocean::SeaState sea_state;                ///< WaveMaker::sea_state: the solver's frame (see the top of the file)
  std::vector<ocean::LatticeWave> carried;  ///< the field's waves it makes, in the field's frame, same order
  std::vector<double> normal_wavenumber_rad_m;      ///< k_L,n of each carried wave (inward, > 0)
  std::vector<double> tangential_wavenumber_rad_m;  ///< l of each carried wave
  double source_depth_m = 0.0;                      ///< d of the source line (what the solver generates in)
  double field_variance_m2 = 0.0;                   ///< sum a^2/2 of every lattice wave of the field
  double carried_variance_m2 = 0.0;                 ///< sum a^2/2 of the carried waves
  InlandPropagation inland;
  BlendingZone blending;

  double variance_fraction() const {
    return field_variance_m2 > 0 ? carried_variance_m2 / field_variance_m2 : 0.0;
  }
  /// eps(s): the relative RMS difference the drift model (top of the file) predicts between the
  /// baked waves and the field's carried waves at distance s inland of the source line.
  double relative_rms_drift(double distance_inland_m) const;
  /// components, variance fraction, carried Hs, source depth, band (for the manifest and the summary).
  sequence::DeepWaterMakerRecord record() const;
};

/// The still-water depth the source line generates in: the mean over the wet cells of the grid line
/// (row or column) holding the source line, as boussinesq_source.cpp computes it. With
/// `effective_depth_limit_m` > 0 every cell counts as at most that deep, as the solver sees it
/// (SolverParameters::effective_depth_limit_m); 0 gives the true depth (the field's).
double source_line_depth_m(const boussinesq::WaveMaker& maker, const HarbourGrid& grid, double effective_depth_limit_m = 0.0);

/// The maker for `field` on `grid`: keeps the lattice waves that travel into the domain from
/// `maker.facing` within the source's 78 degrees, inside `band`, converts them as at the top of the
/// file (maker.source_line_m in the solver's projected frame; B, dt = the solver's
/// dispersion_coefficient and resolved time_step_s), and lays out the blending zone. The sea state's
/// loop period and seed are the field's. Throws nearshore::Error when the field is not at the source
/// line's depth.
CoupledWaveMaker couple_wave_maker(const ocean::DeepWaterField& field, const boussinesq::WaveMaker& maker,
                                   const HarbourGrid& grid, const boussinesq::SolverParameters& solver,
                                   const WaveMakerBand& band);

}  // namespace nearshore::bake
