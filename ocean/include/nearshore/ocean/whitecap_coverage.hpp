#pragma once
// Whitecap coverage by wind speed (issue 41): the fraction of the sea surface that foams, from
// the literature, and the Jacobian foam onset J_b (seed 000 eq. 3.45) at which a synthesised
// deep-water field foams that much.
//
// Monahan & O'Muircheartaigh (1980), "Optimal power-law description of oceanic whitecap coverage
// dependence on wind speed", J. Phys. Oceanogr. 10, 2094-2099:
//     W(U10) = 3.84e-6 U10^3.41          (fraction of the surface; U10 in m/s, 10 m above the sea)
// fitted to shipboard photographs of open-sea whitecaps (stage A crests and stage B decaying foam
// together; its data reach about 20 m/s). Later data reach 23 m/s (Callaghan, de Leeuw, Cohen &
// O'Dowd 2008, GRL 35 L23609, doi:10.1029/2008GL036165: their fit is valid for 3.7-23.1 m/s).
// Coverages published for one wind speed differ by a factor of several between data sets (the
// compilation of Anguelova & Webster 2006, JGR 111 C03017, doi:10.1029/2005JC003158), so a
// coverage within a factor 1.5 of the fit is inside what the data can tell apart. Beyond the
// fitted range the power law is extrapolated: it passes 1 at 38.7 m/s and is clamped there; seed
// 000 table 3.1 says as much in words (force 12, 118 km/h and above: "the whole sea is white").
//
// The coverage definition (one, used everywhere here): the share of the DRAWN surface where the
// water shader's f_b = clamp(J_b - J, 0, 1) is above zero, i.e. where J < J_b. The choppy
// displacement x -> x + lambda D draws a patch of the plane over J times its area, so a compressed
// (foaming) patch takes less of the picture than of the plane: each point counts with weight
// max(J, 0) (folded water, J < 0, lies over other water and adds none). A photograph, from which
// W was measured, sees the drawn surface. J is computed as the shader computes it at full detail
// (shaders/surface.glsl cascade_displacement_gradient: each cascade's displacement differenced
// centrally over one texel, bilinear between samples, summed over cascades; seed 000 eq.
// 3.39-3.44). Why this one: it is exactly the set of surface points
// that the shader paints with deep-water foam this frame (and that foam_decay.frag.glsl starts a
// persistent foam trail from), so matching it to W matches where foam is drawn. The analytic
// derivative channels (ocean::jacobian of DeepWaterFrame::displacement_xx ...) are not what the
// screen shows: central differences damp the shortest waves of each cascade, which carry much of
// the slope. Measured on `nearshore play`'s Beaufort 8 sea at t = 0 (65536 points), J < 0.70 covers
// 1.95 % of it by the analytic channels and 1.35 % by the shader's differences (force 4: 0.72 %
// and 0.39 %): a factor 1.4-1.8, more than the statistics' noise.
//
// J_b is taken from the field's own J distribution (a quantile measured on its samples), not from
// a fitted constant, so it holds for any spectrum, cascade layout and choppiness. It is clamped to
// [kLowestFoamOnsetJacobian, kHighestFoamOnsetJacobian]:
//  - 1: foam wherever the surface is compressed at all (J < 1); above 1 stretched water, which a
//    breaking crest never is, would foam. About half the plane is compressed, and it is drawn
//    over less than half the picture: where W asks for more (above ~30 m/s, Beaufort 11-12), the
//    coverage stays below it (force 12: 45 % for Monahan's 69 %).
//  - 0: foam only where the choppy surface has folded over (J < 0, seed 000 section 3.1.4); a
//    lower J_b would keep foam only inside the folds of the linear model, where even the surface
//    drawn is an artefact. Where W asks for less than the folded fraction (light winds with a
//    large choppiness), the coverage stays above it.
#include <cstddef>
#include <optional>
#include <span>
#include <vector>

#include "nearshore/ocean/deep_water.hpp"

namespace nearshore::ocean {

/// Monahan & O'Muircheartaigh (1980): W = 3.84e-6 U10^3.41, the fraction of the sea surface
/// covered by whitecaps at a wind of `wind_speed_10_m_s` (m/s, 10 m above the sea), clamped to
/// [0, 1]. Throws nearshore::Error naming the parameter for a negative or non-finite wind speed.
double monahan_whitecap_coverage(double wind_speed_10_m_s);

inline constexpr double kLowestFoamOnsetJacobian = 0.0;   ///< J_b floor: only folded water (see above)
inline constexpr double kHighestFoamOnsetJacobian = 1.0;  ///< J_b ceiling: all compressed water

/// J at (x, y) (m) as the water shader computes it with every cascade at full detail: for each
/// cascade, the displacement D_x, D_y bilinear between its samples (i L / N, periodic) and
/// differenced centrally over one sample spacing L / N; the gradients summed over the cascades;
/// J = (1 + lambda dDx/dx)(1 + lambda dDy/dy) - lambda^2 dDx/dy dDy/dx (seed 000 eq. 3.39).
/// `choppiness` is lambda. Frames without displacement give J = 1.
double rendered_jacobian(std::span<const DeepWaterFrame> cascades, double choppiness, double x_m, double y_m);

/// The distribution of the rendered J over a field's surface, pooled over one or more frames.
class JacobianDistribution {
 public:
  /// Adds `sample_count` points of the largest tile (cascades.front()) on a 2-D Kronecker (R2)
  /// low-discrepancy sequence, as foam_statistics places them: they never alias with the smaller
  /// tiles' periods. Throws nearshore::Error naming the parameter for no cascades or a
  /// sample_count below 1.
  void add_frames(std::span<const DeepWaterFrame> cascades, double choppiness, int sample_count);
  int sample_count() const { return static_cast<int>(jacobians_.size()); }
  /// The coverage that J_b = `jacobian_foam_onset` gives: the share of the drawn surface where
  /// J < J_b, each sample weighted by the area it is drawn over, max(J, 0) (see the top).
  double coverage_below(double jacobian_foam_onset) const;
  /// The J_b at which coverage_below reaches `coverage` (in [0, 1]; linear between samples).
  double quantile(double coverage) const;

 private:
  void prepare() const;  // sorts, and sums the drawn area below each sample
  mutable std::vector<double> jacobians_;
  mutable std::vector<double> drawn_area_below_;
  mutable bool sorted_ = true;
};

/// What foam_onset_for_coverage found.
struct FoamOnset {
  double jacobian_foam_onset = kStokesBreakingJacobian;  ///< J_b, within the clamp
  double target_coverage = 0.0;  ///< the coverage asked for (fraction)
  double coverage = 0.0;         ///< the coverage J_b gives on the distribution's samples
  bool clamped = false;          ///< the J_b the target needs lies outside [lowest, highest]
};

/// The J_b at which `target_coverage` (fraction in [0, 1]) of the distribution's samples foam
/// (J < J_b), clamped to [kLowestFoamOnsetJacobian, kHighestFoamOnsetJacobian]. A distribution
/// without samples gives kStokesBreakingJacobian (nothing to match) and coverage 0. Throws nearshore::Error naming the parameter for a target outside [0, 1].
FoamOnset foam_onset_for_coverage(const JacobianDistribution& distribution, double target_coverage);

/// J_b kept at Monahan's W for the deep water a renderer shows (what `nearshore play` uses each
/// frame): measures the distribution of the frames it is given (65536 points) only when the sea
/// differs from the last one measured (largest tile length, cascade count, choppiness) or the
/// wind does; about 30 ms when it measures, nothing otherwise.
class WhitecapFoamOnset {
 public:
  /// The onset for `cascades` (a deep keyframe's frames) at wind `wind_speed_10_m_s` (m/s) when
  /// it measured anew; nullopt when nothing changed or there are no cascades. Throws what
  /// monahan_whitecap_coverage throws.
  std::optional<FoamOnset> update(std::span<const DeepWaterFrame> cascades, double choppiness, double wind_speed_10_m_s);

 private:
  double tile_length_m_ = -1.0, choppiness_ = -1.0, wind_speed_10_m_s_ = -1.0;
  std::size_t cascade_count_ = 0;
};

}  // namespace nearshore::ocean
