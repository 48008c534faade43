#include "nearshore/bake/deep_water_coupling.hpp"

#include "nearshore/boussinesq/model_dispersion.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "nearshore/core/error.hpp"

namespace nearshore::bake {

using namespace nearshore::ocean;       // spectra, sea states, the deep-water field
using namespace nearshore::boussinesq;  // the solver and its parameters
namespace {

constexpr double kPi = std::numbers::pi;

bool normal_is_x(Side facing) {
  return facing == Side::kWest || facing == Side::kEast;
}
// +1 when the waves travel towards +x or +y (from the west or south side), else -1.
double travel_sign(Side facing) {
  return (facing == Side::kWest || facing == Side::kSouth) ? 1.0 : -1.0;
}

const char* side_name(Side side) {
  switch (side) {
    case Side::kWest:
      return "west";
    case Side::kEast:
      return "east";
    case Side::kSouth:
      return "south";
    case Side::kNorth:
      return "north";
  }
  return "south";
}

// The normal wavenumber the discrete solver gives a wave of frequency w and tangential wavenumber l
// at depth d (top of deep_water_coupling.hpp); 0 where the wave does not reach (evanescent).
double discrete_normal_wavenumber_rad_m(double w, double l, double d, const InlandPropagation& model) {
  if (!(d > 0.0)) return 0.0;
  // dx normal to the line, dy along it (rectangular cells: each axis its own size).
  const double dx = model.spacing_m, dy = model.tangential_spacing_m, dt = model.time_step_s;
  const double w_continuous = dt > 0.0 ? 2.0 / dt * std::tan(0.5 * w * dt) : w;  // Crank-Nicolson phase lag
  const double k = boussinesq_wavenumber(w_continuous, d, model.dispersion_coefficient);
  const double l_grid = 2.0 / dy * std::sin(0.5 * l * dy);  // staggered differences: k -> (2/dy) sin(k dy/2)
  const double normal_grid_squared = k * k - l_grid * l_grid;
  if (!(normal_grid_squared > 0.0)) return 0.0;
  return 2.0 / dx * std::asin(std::min(1.0, 0.5 * dx * std::sqrt(normal_grid_squared)));
}

// cos(theta) of the continuous wave at depth d with tangential wavenumber l (Snell), 0 if evanescent.
double normal_cosine(double w, double l, double d, double dispersion_coefficient) {
  if (!(d > 0.0)) return 0.0;
  const double k = boussinesq_wavenumber(w, d, dispersion_coefficient);
  return k > std::abs(l) ? std::sqrt(1.0 - (l / k) * (l / k)) : 0.0;
}

}  // namespace

double BlendingZone::distance_inland_m(double x_m, double y_m) const {
  return travel_sign(side) * ((normal_is_x(side) ? x_m : y_m) - source_line_m);
}

double BlendingZone::baked_weight(double distance_inland_m) const {
  if (distance_inland_m <= start_m) return 0.0;
  if (distance_inland_m >= start_m + width_m) return 1.0;
  const double s = std::sin(0.5 * kPi * (distance_inland_m - start_m) / width_m);
  return s * s;
}

sequence::DeepWaterBlendingRecord BlendingZone::record() const {
  return {side_name(side),        normal_is_x(side) ? "x" : "y",  source_line_m, start_m,
          width_m,                predicted_relative_rms_start,   predicted_relative_rms_end,
          seamless,               kSeamlessRelativeRms};
}

double CoupledWaveMaker::relative_rms_drift(double distance_inland_m) const {
  // Per wave: the phase drift delta by the midpoint rule over the grid lines (step dx), and the
  // shoaling-refraction factor K at s; then eps^2 = sum a^2 (1 + K^2 - 2 K cos delta) / sum a^2.
  const double s = std::max(0.0, distance_inland_m);
  const double dx = inland.spacing_m;
  const auto depth_at = [&](double at_m) {
    if (inland.depth_m.empty()) return source_depth_m;
    const auto j = static_cast<std::size_t>(std::lround(at_m / dx));
    return inland.depth_m[std::min(j, inland.depth_m.size() - 1)];
  };
  double difference = 0.0, reference = 0.0;
  for (std::size_t i = 0; i < carried.size(); ++i) {
    const double a = carried[i].wave.amplitude_m, w = carried[i].wave.angular_frequency_rad_s;
    const double l = tangential_wavenumber_rad_m[i], lattice_normal = normal_wavenumber_rad_m[i];
    double delta = 0.0;
    for (double from = 0.0; from < s; from += dx) {
      const double step = std::min(dx, s - from);
      delta +=
          (discrete_normal_wavenumber_rad_m(w, l, depth_at(from + 0.5 * step), inland) - lattice_normal) *
          step;
    }
    const double d = depth_at(s), B = inland.dispersion_coefficient;
    const double flux_there =
        d > 0.0 ? group_speed_m_s(wavenumber_from_frequency(w, d), d) * normal_cosine(w, l, d, B) : 0.0;
    const double flux_here = group_speed_m_s(wavenumber_from_frequency(w, source_depth_m), source_depth_m) *
                             normal_cosine(w, l, source_depth_m, B);
    const double shoaling = flux_there > 0.0 ? std::sqrt(flux_here / flux_there) : 0.0;
    difference += a * a * (1.0 + shoaling * shoaling - 2.0 * shoaling * std::cos(delta));
    reference += a * a;
  }
  return reference > 0 ? std::sqrt(difference / reference) : 0.0;
}

sequence::DeepWaterMakerRecord CoupledWaveMaker::record() const {
  double lowest = 0.0, highest = 0.0;
  if (!sea_state.components.empty()) {
    const auto [low, high] =
        std::minmax_element(sea_state.components.begin(), sea_state.components.end(),
                            [](const WaveComponent& a, const WaveComponent& b) {
                              return a.angular_frequency_rad_s < b.angular_frequency_rad_s;
                            });
    lowest = low->angular_frequency_rad_s;
    highest = high->angular_frequency_rad_s;
  }
  return {sea_state.components.size(),
          variance_fraction(),
          field_variance_m2,
          carried_variance_m2,
          4.0 * std::sqrt(carried_variance_m2),
          source_depth_m,
          lowest / (2 * kPi),
          highest / (2 * kPi)};
}

namespace {
// The depth the solver sees in a cell (boussinesq_solver.cpp: min(d, limit) where a limit is set).
double seen_depth_m(double depth_m, double effective_depth_limit_m) {
  return effective_depth_limit_m > 0.0 ? std::min(depth_m, effective_depth_limit_m) : depth_m;
}
}  // namespace

double source_line_depth_m(const WaveMaker& maker, const HarbourGrid& grid, double effective_depth_limit_m) {
  // As boussinesq_source.cpp: the grid line of cell index round((line - origin) / dx - 0.5), the
  // mean of its cells deeper than 0 m summed along the line's span, in double from the float raster.
  const GridGeometry& g = grid.geometry;
  const bool along_x = normal_is_x(maker.facing);
  const int normal_count = along_x ? g.columns : g.rows, tangential_count = along_x ? g.rows : g.columns;
  const double line_index =
      (maker.source_line_m - (along_x ? g.origin_x_m : g.origin_y_m)) / (along_x ? g.spacing_x_m() : g.spacing_y_m()) - 0.5;
  const int line_cell = std::clamp(static_cast<int>(std::lround(line_index)), 0, normal_count - 1);
  double sum_m = 0.0;
  int wet = 0;
  // Over the maker's span only (WaveMaker::span_begin_cell), as the source function.
  const int span_begin = std::clamp(maker.span_begin_cell, 0, tangential_count);
  const int span_end = std::clamp(maker.span_end_cell, span_begin, tangential_count);
  for (int t = span_begin; t < span_end; ++t) {
    const double d = seen_depth_m(along_x ? grid.still_water_depth_m(line_cell, t) : grid.still_water_depth_m(t, line_cell),
                                  effective_depth_limit_m);
    if (d > 0.0) sum_m += d, ++wet;
  }
  return wet > 0 ? sum_m / wet : 0.0;
}

CoupledWaveMaker couple_wave_maker(const DeepWaterField& field, const WaveMaker& maker,
                                   const HarbourGrid& grid, const SolverParameters& solver,
                                   const WaveMakerBand& band) {
  const double dispersion_coefficient = solver.dispersion_coefficient;
  CoupledWaveMaker coupled;
  const GridGeometry& g = grid.geometry;
  const bool along_x = normal_is_x(maker.facing);
  const double sign = travel_sign(maker.facing);
  // The field is built at the true depth of the source line (Airy, the sea as it is); the maker
  // converts its waves with the depth the solver sees there, which an effective-depth limit may make
  // shallower (docs/solver.md, "Effective depth": within its phase-speed tolerance of the field's).
  const double true_depth_m = source_line_depth_m(maker, grid);
  const double d = source_line_depth_m(maker, grid, solver.effective_depth_limit_m);
  coupled.source_depth_m = d;
  const double field_depth_m = field.specification().still_water_depth_m;
  if (!(d > 0.0) || std::abs(field_depth_m - true_depth_m) > 1e-6 * std::max(1.0, true_depth_m))
    throw Error(
        "deep-water field",
        fmt::format("is built at {} m depth, but the source line generates in {} m", field_depth_m, true_depth_m),
        "build the field at the source line's depth (leave deep_water.depth_m out), so both have one "
        "dispersion relation");
  // 1. Positions along the normal (n) and tangential (t) axes: the line's projected S_line and local
  // s_line, the origin's T_0 (see the top of deep_water_coupling.hpp).
  const double line_projected_m = maker.source_line_m;
  const double line_local_m = line_projected_m - (along_x ? g.origin_x_m : g.origin_y_m);
  const double tangential_origin_m = along_x ? g.origin_y_m : g.origin_x_m;

  // 2. The lattice waves the maker makes, converted (top of deep_water_coupling.hpp).
  const std::vector<LatticeWave> lattice = field.lattice_waves();
  double largest_m = 0.0;
  for (const LatticeWave& wave : lattice) {
    largest_m = std::max(largest_m, wave.wave.amplitude_m);
    coupled.field_variance_m2 += 0.5 * wave.wave.amplitude_m * wave.wave.amplitude_m;
  }
  coupled.sea_state.loop_period_s = field.specification().loop_period_s;
  coupled.sea_state.seed = field.specification().seed;
  for (const LatticeWave& wave : lattice) {
    const WaveComponent& c = wave.wave;
    const double w = c.angular_frequency_rad_s;
    const double lattice_normal =
        along_x ? wave.wavenumber_x_rad_m : wave.wavenumber_y_rad_m;  // signed along the axis
    const double l = along_x ? wave.wavenumber_y_rad_m : wave.wavenumber_x_rad_m;
    if (lattice_normal * sign <= 0.0 || w < band.min_frequency_rad_s || w > band.max_frequency_rad_s ||
        c.amplitude_m < band.min_amplitude_ratio * largest_m)
      continue;
    const double k_model = boussinesq_wavenumber(w, d, dispersion_coefficient);
    const double normal_squared = k_model * k_model - l * l;
    if (normal_squared < std::pow(band.min_normal_fraction * k_model, 2))
      continue;  // beyond the largest angle to the normal
    const double model_normal = sign * std::sqrt(normal_squared);
    WaveComponent made = c;
    made.direction_rad = along_x ? std::atan2(l, model_normal) : std::atan2(model_normal, l);
    // The wavevector exactly as the source will compute it from the direction (boussinesq_source.cpp).
    const double kx = k_model * std::cos(made.direction_rad), ky = k_model * std::sin(made.direction_rad);
    const double source_normal = along_x ? kx : ky, source_tangential = along_x ? ky : kx;
    const double phase = c.phase_rad + lattice_normal * line_local_m - source_normal * line_projected_m -
                         source_tangential * tangential_origin_m;
    made.phase_rad = phase - 2 * kPi * std::floor(phase / (2 * kPi));
    coupled.sea_state.components.push_back(made);
    coupled.carried.push_back(wave);
    coupled.normal_wavenumber_rad_m.push_back(sign * lattice_normal);
    coupled.tangential_wavenumber_rad_m.push_back(l);
    coupled.carried_variance_m2 += 0.5 * c.amplitude_m * c.amplitude_m;
  }

  // 3. What the solver does inland (the drift model): its dx, dt and B, and the mean wet depth of
  //    every grid line parallel to the source line, from the line's own to the far edge.
  coupled.inland.spacing_m = along_x ? g.spacing_x_m() : g.spacing_y_m();
  coupled.inland.tangential_spacing_m = along_x ? g.spacing_y_m() : g.spacing_x_m();
  coupled.inland.time_step_s = solver.time_step_s;
  coupled.inland.dispersion_coefficient = dispersion_coefficient;
  const int normal_count = along_x ? g.columns : g.rows, tangential_count = along_x ? g.rows : g.columns;
  const double line_index = line_local_m / coupled.inland.spacing_m - 0.5;  // fractional cell index of the line
  for (int j = 0;; ++j) {
    const int cell = static_cast<int>(std::lround(line_index + sign * j));
    if (cell < 0 || cell >= normal_count) break;
    double sum_m = 0.0;
    int wet = 0;
    for (int t = 0; t < tangential_count; ++t) {
      const double depth = seen_depth_m(along_x ? grid.still_water_depth_m(cell, t) : grid.still_water_depth_m(t, cell),
                                        solver.effective_depth_limit_m);
      if (depth > 0.0) sum_m += depth, ++wet;
    }
    coupled.inland.depth_m.push_back(wet > 0 ? sum_m / wet : 0.0);
  }

  // 4. The blending zone. The source strip is +-3 / sqrt(beta), beta = 20 / L^2, L the model
  //    wavelength of the shortest component (boussinesq_source.cpp, docs/solver.md "Wave maker"):
  //    inside it the field is the outgoing wave plus the source's near field, beyond it (Gaussian
  //    < e^-9) the outgoing wave alone. The zone starts at 3 L_p / sqrt(20), L_p the largest
  //    component's wavelength: the strip's edge when the source is one wave, beyond it otherwise.
  //    The cross-fade takes the next peak wavelength, or less (not below half of it) where the
  //    predicted difference would pass the seam criterion before.
  BlendingZone& zone = coupled.blending;
  zone.side = maker.facing;
  zone.source_line_m = line_local_m;
  if (!coupled.sea_state.components.empty()) {
    const auto peak = std::max_element(
        coupled.sea_state.components.begin(), coupled.sea_state.components.end(),
        [](const WaveComponent& a, const WaveComponent& b) { return a.amplitude_m < b.amplitude_m; });
    const double peak_wavelength_m =
        2 * kPi / boussinesq_wavenumber(peak->angular_frequency_rad_s, d, dispersion_coefficient);
    zone.start_m = 3.0 * peak_wavelength_m / std::sqrt(20.0);
    zone.width_m = peak_wavelength_m;
    const auto end_error = [&](double width_m) { return coupled.relative_rms_drift(zone.start_m + width_m); };
    if (end_error(zone.width_m) > kSeamlessRelativeRms) {
      double seamless_m = 0.5 * peak_wavelength_m, too_wide_m = peak_wavelength_m;
      if (end_error(seamless_m) > kSeamlessRelativeRms) too_wide_m = seamless_m;
      for (int iteration = 0; iteration < 30 && too_wide_m - seamless_m > 0.01 * coupled.inland.spacing_m; ++iteration) {
        const double middle_m = 0.5 * (seamless_m + too_wide_m);
        (end_error(middle_m) > kSeamlessRelativeRms ? too_wide_m : seamless_m) = middle_m;
      }
      zone.width_m = seamless_m;
    }
    zone.predicted_relative_rms_start = coupled.relative_rms_drift(zone.start_m);
    zone.predicted_relative_rms_end = end_error(zone.width_m);
    zone.seamless = zone.predicted_relative_rms_end <= kSeamlessRelativeRms;
  }
  return coupled;
}

}  // namespace nearshore::bake
