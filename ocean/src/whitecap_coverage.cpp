#include "nearshore/ocean/whitecap_coverage.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "nearshore/core/error.hpp"

namespace nearshore::ocean {

double monahan_whitecap_coverage(double wind_speed_10_m_s) {
  if (!(wind_speed_10_m_s >= 0.0) || !std::isfinite(wind_speed_10_m_s))
    throw Error("whitecap coverage", fmt::format("the wind speed U10 = {} m/s is not a speed", wind_speed_10_m_s),
                "give wind_speed_10_m_s as a finite number of m/s, 0 or more");
  // Monahan & O'Muircheartaigh (1980): W = 3.84e-6 U10^3.41 (fraction); 1 from 38.7 m/s on.
  return std::min(1.0, 3.84e-6 * std::pow(wind_speed_10_m_s, 3.41));
}

double rendered_jacobian(std::span<const DeepWaterFrame> cascades, double choppiness, double x_m, double y_m) {
  // The gradient (dDx/dx, dDy/dy, dDx/dy, dDy/dx) summed over the cascades, each as
  // shaders/surface.glsl cascade_displacement_gradient reads it: the bilinear displacement one
  // sample spacing h = L / N either side, (D(p + h) - D(p - h)) / 2h.
  double gxx = 0.0, gyy = 0.0, gxy = 0.0, gyx = 0.0;
  for (const DeepWaterFrame& frame : cascades) {
    if (frame.displacement_x_m.empty() || frame.displacement_y_m.empty()) continue;
    const int n = frame.grid_size;
    const double u = x_m / frame.tile_length_m * n, v = y_m / frame.tile_length_m * n;
    const double u0 = std::floor(u), v0 = std::floor(v);
    const double fu = u - u0, fv = v - v0;
    auto wrap = [n](long long p) { return static_cast<int>(((p % n) + n) % n); };
    const long long c = static_cast<long long>(u0), r = static_cast<long long>(v0);
    // Bilinear at the sample position shifted by (dc, dr) whole samples.
    auto bilinear = [&](const std::vector<float>& field, int dc, int dr) {
      const int c0 = wrap(c + dc), c1 = wrap(c + dc + 1), r0 = wrap(r + dr), r1 = wrap(r + dr + 1);
      auto at = [&](int row, int column) { return static_cast<double>(field[static_cast<std::size_t>(row) * n + column]); };
      return (1 - fv) * ((1 - fu) * at(r0, c0) + fu * at(r0, c1)) + fv * ((1 - fu) * at(r1, c0) + fu * at(r1, c1));
    };
    const double twice_spacing_m = 2.0 * frame.tile_length_m / n;
    gxx += (bilinear(frame.displacement_x_m, 1, 0) - bilinear(frame.displacement_x_m, -1, 0)) / twice_spacing_m;
    gyy += (bilinear(frame.displacement_y_m, 0, 1) - bilinear(frame.displacement_y_m, 0, -1)) / twice_spacing_m;
    gxy += (bilinear(frame.displacement_x_m, 0, 1) - bilinear(frame.displacement_x_m, 0, -1)) / twice_spacing_m;
    gyx += (bilinear(frame.displacement_y_m, 1, 0) - bilinear(frame.displacement_y_m, -1, 0)) / twice_spacing_m;
  }
  const double lambda = choppiness;
  return (1.0 + lambda * gxx) * (1.0 + lambda * gyy) - lambda * lambda * gxy * gyx;  // seed 000 eq. (3.39)
}

void JacobianDistribution::add_frames(std::span<const DeepWaterFrame> cascades, double choppiness, int sample_count) {
  if (cascades.empty())
    throw Error("Jacobian distribution", "the frames to add hold no cascade", "synthesise the deep-water field first");
  if (sample_count < 1)
    throw Error("Jacobian distribution", fmt::format("sample_count = {} points per frame", sample_count),
                "give sample_count of 1 or more (65536 resolves a coverage of 0.1 % to about 4 %)");
  // R2 sequence (Roberts 2018) over the largest tile, as foam_statistics places its points.
  constexpr double plastic = 1.32471795724474602596;
  const double largest_tile_m = cascades.front().tile_length_m;
  jacobians_.reserve(jacobians_.size() + static_cast<std::size_t>(sample_count));
  for (int j = 1; j <= sample_count; ++j) {
    const double u = std::fmod(j / plastic, 1.0), v = std::fmod(j / (plastic * plastic), 1.0);
    jacobians_.push_back(rendered_jacobian(cascades, choppiness, u * largest_tile_m, v * largest_tile_m));
  }
  sorted_ = false;
}

void JacobianDistribution::prepare() const {
  if (sorted_) return;
  std::sort(jacobians_.begin(), jacobians_.end());
  // A point of the undisplaced plane with Jacobian J is drawn over J times its area (x -> x + lambda D);
  // where the surface has folded (J < 0) it is drawn over another, and adds no area of its own.
  drawn_area_below_.assign(jacobians_.size() + 1, 0.0);
  for (std::size_t i = 0; i < jacobians_.size(); ++i) drawn_area_below_[i + 1] = drawn_area_below_[i] + std::max(jacobians_[i], 0.0);
  sorted_ = true;
}

double JacobianDistribution::coverage_below(double jacobian_foam_onset) const {
  if (jacobians_.empty()) return 0.0;
  prepare();
  if (drawn_area_below_.back() <= 0.0) return 0.0;
  const auto below = std::lower_bound(jacobians_.begin(), jacobians_.end(), jacobian_foam_onset) - jacobians_.begin();
  return drawn_area_below_[static_cast<std::size_t>(below)] / drawn_area_below_.back();
}

double JacobianDistribution::quantile(double coverage) const {
  if (jacobians_.empty()) return 1.0;
  prepare();
  // The smallest J_b whose drawn area below reaches `coverage` of the whole: coverage_below is
  // a step function of J_b rising at each sample; between two samples, linear.
  const double wanted = std::clamp(coverage, 0.0, 1.0) * drawn_area_below_.back();
  const auto step = std::lower_bound(drawn_area_below_.begin(), drawn_area_below_.end(), wanted) - drawn_area_below_.begin();
  if (step <= 0) return jacobians_.front();
  const auto i = static_cast<std::size_t>(step) - 1;  // drawn_area_below_[i] < wanted <= drawn_area_below_[i + 1]
  if (i + 1 >= jacobians_.size()) return jacobians_.back();
  const double share = (wanted - drawn_area_below_[i]) / std::max(drawn_area_below_[i + 1] - drawn_area_below_[i], 1e-300);
  return jacobians_[i] + share * (jacobians_[i + 1] - jacobians_[i]);
}

FoamOnset foam_onset_for_coverage(const JacobianDistribution& distribution, double target_coverage) {
  if (!(target_coverage >= 0.0 && target_coverage <= 1.0))
    throw Error("whitecap coverage", fmt::format("the target coverage {} is not a fraction of the surface", target_coverage),
                "give target_coverage in [0, 1] (monahan_whitecap_coverage gives one)");
  FoamOnset onset;
  onset.target_coverage = target_coverage;
  if (distribution.sample_count() == 0) return onset;
  const double wanted = distribution.quantile(target_coverage);
  onset.jacobian_foam_onset = std::clamp(wanted, kLowestFoamOnsetJacobian, kHighestFoamOnsetJacobian);
  onset.clamped = onset.jacobian_foam_onset != wanted;
  onset.coverage = distribution.coverage_below(onset.jacobian_foam_onset);
  return onset;
}

std::optional<FoamOnset> WhitecapFoamOnset::update(std::span<const DeepWaterFrame> cascades, double choppiness,
                                                   double wind_speed_10_m_s) {
  if (cascades.empty()) return std::nullopt;
  if (cascades.front().tile_length_m == tile_length_m_ && cascades.size() == cascade_count_ &&
      choppiness == choppiness_ && wind_speed_10_m_s == wind_speed_10_m_s_)
    return std::nullopt;
  const double target = monahan_whitecap_coverage(wind_speed_10_m_s);
  JacobianDistribution distribution;
  distribution.add_frames(cascades, choppiness, 65536);
  tile_length_m_ = cascades.front().tile_length_m, cascade_count_ = cascades.size();
  choppiness_ = choppiness, wind_speed_10_m_s_ = wind_speed_10_m_s;
  return foam_onset_for_coverage(distribution, target);
}

}  // namespace nearshore::ocean
