#include "nearshore/boussinesq/porous_layer_flume.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

#include <fmt/core.h>

#include "nearshore/boussinesq/incident_reflected.hpp"
#include "nearshore/boussinesq/model_dispersion.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/ocean/linear_waves.hpp"

namespace nearshore::boussinesq {
namespace {

constexpr const char* kSubject = "porous layer flume";
constexpr double kPi = std::numbers::pi;

void check(const char* field, double value, double lowest, double highest, const char* why) {
  if (!(value >= lowest && value <= highest))
    throw Error(kSubject, fmt::format("PorousLayerFlume::{} = {} is outside {} .. {} ({})", field, value, lowest, highest, why),
                fmt::format("give PorousLayerFlume::{} inside that range", field));
}

// Gauge cells from `start_m`, spanning 0.4 L at about 0.1 L apart on whole cells (Mansard & Funke:
// no spacing a multiple of L/2); at least three distinct cells.
std::vector<int> gauge_cells(double start_m, double wavelength_m, double spacing_m) {
  std::vector<int> cells;
  for (int j = 0; j <= 4; ++j) {
    const int cell = static_cast<int>(std::floor((start_m + 0.1 * j * wavelength_m) / spacing_m));
    if (cells.empty() || cell != cells.back()) cells.push_back(cell);
  }
  while (cells.size() < 3) cells.push_back(cells.back() + 1);
  return cells;
}

}  // namespace

LayerResponse measure_porous_layer(const PorousLayerFlume& flume, double porosity) {
  check("still_water_depth_m", flume.still_water_depth_m, 0.05, 500.0, "water a porous layer stands in");
  check("wave_period_s", flume.wave_period_s, 0.2, 60.0, "wind waves and swell");
  check("wave_height_m", flume.wave_height_m, 1e-4, 0.6 * flume.still_water_depth_m, "below breaking, 0.6 d");
  check("spacing_m", flume.spacing_m, 1e-3, 1000.0, "a cell size");
  check("layer_width_m", flume.layer_width_m, 0.5 * flume.spacing_m, 5000.0, "at least one cell");
  if (!(porosity > kWallPorosity && porosity <= 1.0))
    throw Error(kSubject, fmt::format("porosity {} is outside ({} .. 1]", porosity, kWallPorosity),
                "a porosity at or below kWallPorosity is a wall, not a layer");
  const double depth_m = flume.solver.effective_depth_limit_m > 0.0 ? std::min(flume.still_water_depth_m, flume.solver.effective_depth_limit_m)
                                                                     : flume.still_water_depth_m;
  const double w = 2.0 * kPi / flume.wave_period_s;
  const double k = boussinesq_wavenumber(w, depth_m, flume.solver.dispersion_coefficient);
  const double L = 2.0 * kPi / k, dx = flume.spacing_m;
  const int layer_cells = std::max(1, static_cast<int>(std::lround(flume.layer_width_m / dx)));

  // Layout (header): lengths in metres, rounded to whole cells.
  auto cells_of = [dx](double length_m) { return static_cast<int>(std::ceil(length_m / dx)); };
  const double west_sponge_m = std::max(1.5 * L, 8.0 * dx);
  const double source_m = west_sponge_m + std::max(L, 6.0 * dx);
  const double gauges_m = source_m + std::max(0.8 * L, 4.0 * dx);
  const std::vector<int> front_gauges = gauge_cells(gauges_m, L, dx);
  const int layer_first = front_gauges.back() + 1 + cells_of(std::max(0.6 * L, 3.0 * dx));
  const int layer_last = layer_first + layer_cells - 1;
  std::vector<int> back_gauges;
  int columns = layer_last + 1;
  double east_sponge_m = 0.0;
  if (!flume.wall_behind) {
    back_gauges = gauge_cells((layer_last + 1) * dx + std::max(0.8 * L, 4.0 * dx), L, dx);
    east_sponge_m = std::max(2.0 * L, 8.0 * dx);
    columns = back_gauges.back() + 1 + cells_of(std::max(0.6 * L, 3.0 * dx)) + cells_of(east_sponge_m);
  }
  if (static_cast<double>(columns) > 2e5)
    throw Error(kSubject, fmt::format("{:.0f} m cells against a {:.0f} m wave need {} cells", dx, L, columns),
                "use cells of at least 1/50 of the wavelength");

  GridGeometry geometry;
  geometry.columns = columns;
  geometry.rows = 1;
  geometry.spacing_m = dx;
  HarbourGrid harbour = HarbourGrid::open_water(geometry, static_cast<float>(flume.still_water_depth_m));
  for (int c = layer_first; c <= layer_last; ++c) harbour.porosity(c, 0) = static_cast<float>(porosity);

  SolverParameters parameters = flume.solver;
  parameters.breaking.enabled = false;
  parameters.sponges = {{Side::kWest, west_sponge_m}};
  if (!flume.wall_behind) parameters.sponges.push_back({Side::kEast, east_sponge_m});
  // A whole number of steps per period (Courant <= 0.5): the harmonic analysis is then exact.
  const double courant_dt = 0.5 * dx / std::sqrt(ocean::kGravity_m_s2 * flume.still_water_depth_m);
  const int steps_per_period = std::max(8, static_cast<int>(std::ceil(flume.wave_period_s / courant_dt)));
  parameters.time_step_s = flume.wave_period_s / steps_per_period;
  WaveMaker maker;
  maker.kind = WaveMaker::Kind::kComponents;
  maker.sea_state.components = {{0.5 * flume.wave_height_m, w, 0.0, 0.0}};
  maker.source_line_m = source_m;
  maker.facing = Side::kWest;
  maker.ramp_time_s = 2.0 * flume.wave_period_s;
  BoussinesqSolver solver(harbour, parameters, maker);

  // Steady once the front (group speed) has gone source -> east end -> back past the front gauges
  // (two crossings; the source line lets the reflected wave through to the west sponge, so nothing
  // comes back a second time but the sponge's per cent), with half a crossing and the ramp to spare.
  const double group_speed_m_s = ocean::group_speed_m_s(k, depth_m);
  const double crossing_s = (columns * dx - source_m) / group_speed_m_s;
  const int spin_up_periods = static_cast<int>(std::ceil((3.0 * flume.wave_period_s + 2.5 * crossing_s) / flume.wave_period_s));
  const int record_periods = 4;
  const long first_step = static_cast<long>(spin_up_periods) * steps_per_period;
  const long last_step = first_step + static_cast<long>(record_periods) * steps_per_period;
  std::vector<int> all_gauges = front_gauges;
  all_gauges.insert(all_gauges.end(), back_gauges.begin(), back_gauges.end());
  std::vector<std::vector<double>> records(all_gauges.size());
  const auto& eta = solver.surface_elevation_m().values();
  for (long step = 1; step <= last_step; ++step) {
    solver.step();
    if (step % 200 == 0 || step == last_step)
      if (const auto report = solver.check_stability())
        throw Error(kSubject, fmt::format("the flume run became unstable at t = {:.1f} s ({}) with porosity {}", report->time_s, report->what, porosity),
                    "check the solver parameters of the case (time step, porous resistance)");
    if (step <= first_step) continue;
    for (std::size_t g = 0; g < all_gauges.size(); ++g) records[g].push_back(eta[static_cast<std::size_t>(all_gauges[g])]);
  }
  auto separate = [&](std::size_t first, std::size_t count) {
    std::vector<double> positions;
    std::vector<std::complex<double>> amplitudes;
    for (std::size_t g = first; g < first + count; ++g) {
      positions.push_back(geometry.cell_centre_x_m(all_gauges[g]));
      amplitudes.push_back(harmonic_amplitude(records[g], (first_step + 1) * parameters.time_step_s, parameters.time_step_s, w));
    }
    return separate_incident_reflected(positions, amplitudes, k);
  };
  const IncidentReflected front = separate(0, front_gauges.size());
  LayerResponse response;
  response.porosity = porosity;
  response.reflection_coefficient = front.reflection_coefficient();
  response.relative_depth_kh = k * depth_m;
  response.layer_width_wavelengths = layer_cells * dx / L;
  if (!flume.wall_behind) {
    const IncidentReflected back = separate(front_gauges.size(), back_gauges.size());
    response.transmission_coefficient = std::abs(back.incident) / std::abs(front.incident);
  }
  return response;
}

namespace {

// Regula falsi (Illinois variant) on n between `low` and `high`, whose values straddle `target`;
// value(n) monotone on the interval. Converges in a few runs where bisection would take six.
template <typename Value>
PorosityFit regula_falsi(const PorousLayerFlume& flume, double target, double tolerance, LayerResponse low, LayerResponse high,
                         Value&& value, int runs) {
  PorosityFit fit;
  fit.flume_runs = runs;
  double f_low = value(low) - target, f_high = value(high) - target;
  int side = 0;
  for (int i = 0; i < 16; ++i) {
    const LayerResponse& closer = std::abs(f_low) < std::abs(f_high) ? low : high;
    if (std::min(std::abs(f_low), std::abs(f_high)) <= tolerance || std::abs(high.porosity - low.porosity) < 1e-3) {
      fit.response = closer;
      return fit;
    }
    double n = (low.porosity * f_high - high.porosity * f_low) / (f_high - f_low);
    // Keep the new point inside the bracket by a margin (a flat end would stall the secant).
    const double margin = 0.05 * std::abs(high.porosity - low.porosity);
    n = std::clamp(n, std::min(low.porosity, high.porosity) + margin, std::max(low.porosity, high.porosity) - margin);
    const LayerResponse middle = measure_porous_layer(flume, n);
    ++fit.flume_runs;
    const double f_middle = value(middle) - target;
    if (f_low * f_middle <= 0.0) {
      high = middle, f_high = f_middle;
      if (side == -1) f_low *= 0.5;  // Illinois: halve the end that stayed twice
      side = -1;
    } else {
      low = middle, f_low = f_middle;
      if (side == 1) f_high *= 0.5;
      side = 1;
    }
  }
  fit.response = std::abs(f_low) < std::abs(f_high) ? low : high;
  return fit;
}

}  // namespace

PorosityFit fit_porosity_to_reflection(const PorousLayerFlume& flume, double reflection_coefficient, double tolerance) {
  if (!flume.wall_behind)
    throw Error(kSubject, "a reflection is fitted for a layer in front of a wall (PorousLayerFlume::wall_behind = false)",
                "fit the transmission of a free-standing layer instead");
  check("reflection coefficient", reflection_coefficient, 0.0, 1.0, "a fraction of the incident height");
  // The chart of Kr against n, walked from nearly open (Kr -> 1, the wall alone) towards nearly
  // closed (Kr -> 1 again, the layer itself a wall) until it brackets the request or turns up past
  // its minimum; the branch above the minimum is the one fitted.
  const double chart_porosity[] = {0.98, 0.8, 0.6, 0.42, 0.28, 0.17, kLowestFittedPorosity};
  std::vector<LayerResponse> chart;
  auto kr = [](const LayerResponse& r) { return r.reflection_coefficient; };
  for (double n : chart_porosity) {
    chart.push_back(measure_porous_layer(flume, n));
    const int runs = static_cast<int>(chart.size());
    const LayerResponse& last = chart.back();
    if (runs == 1) {
      if (reflection_coefficient >= kr(last) - tolerance) return {last, reflection_coefficient <= kr(last) + tolerance, runs};
      continue;
    }
    const LayerResponse& before = chart[chart.size() - 2];
    if (kr(last) <= reflection_coefficient) return regula_falsi(flume, reflection_coefficient, tolerance, last, before, kr, runs);
    if (kr(last) > kr(before)) break;  // past the minimum without reaching the request
  }
  // The request lies below the chart's minimum: the closest the layer gets, refined by a golden-
  // section step either side of the lowest point.
  const auto lowest = std::min_element(chart.begin(), chart.end(), [&](const auto& a, const auto& b) { return kr(a) < kr(b); });
  LayerResponse best = *lowest;
  int runs = static_cast<int>(chart.size());
  const std::size_t at = static_cast<std::size_t>(lowest - chart.begin());
  for (std::size_t neighbour : {at == 0 ? at : at - 1, std::min(at + 1, chart.size() - 1)}) {
    if (neighbour == at) continue;
    const LayerResponse between = measure_porous_layer(flume, 0.5 * (chart[neighbour].porosity + lowest->porosity));
    ++runs;
    if (kr(between) < kr(best)) best = between;
  }
  return {best, reflection_coefficient >= kr(best) - tolerance, runs};
}

PorosityFit fit_porosity_to_transmission(const PorousLayerFlume& flume, double transmission_coefficient, double tolerance) {
  if (flume.wall_behind)
    throw Error(kSubject, "a transmission is fitted for a layer with open water behind it (PorousLayerFlume::wall_behind = true)",
                "set wall_behind = false");
  check("transmission coefficient", transmission_coefficient, 0.0, 1.0, "a fraction of the incident height");
  const LayerResponse closed = measure_porous_layer(flume, kLowestFittedPorosity);
  const LayerResponse open = measure_porous_layer(flume, 0.98);
  auto kt = [](const LayerResponse& r) { return r.transmission_coefficient; };
  if (transmission_coefficient <= closed.transmission_coefficient + tolerance)
    return {closed, transmission_coefficient >= closed.transmission_coefficient - tolerance, 2};
  if (transmission_coefficient >= open.transmission_coefficient - tolerance)
    return {open, transmission_coefficient <= open.transmission_coefficient + tolerance, 2};
  return regula_falsi(flume, transmission_coefficient, tolerance, closed, open, kt, 2);
}

}  // namespace nearshore::boussinesq
