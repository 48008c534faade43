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
// Wall cells behind a layer: two, as a breakwater's core is at least one cell across and the
// scheme's stencils reach one cell into it.
constexpr int kWallCells = 2;

void check(const char* field, double value, double lowest, double highest, const char* why) {
  if (!(value >= lowest && value <= highest))
    throw Error(kSubject, fmt::format("PorousLayerFlume::{} = {} is outside {} .. {} ({})", field, value, lowest, highest, why),
                fmt::format("give PorousLayerFlume::{} inside that range", field));
}

// `response` with `member` (Kr or Kt, the whole and per wave) divided by the reference run's (the
// same flume at n = 1): the layer's own coefficient, without the bed friction and the scheme on
// the way, which the reference run has too.
LayerResponse relative_to(const LayerResponse& reference, double LayerResponse::*member, LayerResponse response) {
  if (reference.*member > 0.0) response.*member /= reference.*member;
  for (std::size_t i = 0; i < response.per_wave.size() && i < reference.per_wave.size(); ++i)
    if (reference.per_wave[i].*member > 0.0) response.per_wave[i].*member /= reference.per_wave[i].*member;
  return response;
}

// Gauge cells from `start_m` about 0.1 of the shortest wavelength apart on whole cells, spanning 0.4
// of the longest (Mansard & Funke: no spacing a multiple of any wave's L/2 for all pairs); at least
// three distinct cells, at most sixteen.
std::vector<int> gauge_cells(double start_m, double shortest_wavelength_m, double longest_wavelength_m, double spacing_m) {
  const double span_m = 0.4 * longest_wavelength_m;
  const double apart_m = std::max(0.1 * shortest_wavelength_m, span_m / 15.0);
  std::vector<int> cells;
  for (double offset_m = 0.0; offset_m <= span_m + 1e-9; offset_m += apart_m) {
    const int cell = static_cast<int>(std::floor((start_m + offset_m) / spacing_m));
    if (cells.empty() || cell != cells.back()) cells.push_back(cell);
  }
  while (cells.size() < 3) cells.push_back(cells.back() + 1);
  return cells;
}

}  // namespace

LayerResponse measure_porous_layer(const PorousLayerFlume& flume, double porosity) {
  check("still_water_depth_m", flume.still_water_depth_m, 0.05, 500.0, "water a porous layer stands in");
  if (flume.waves.empty() || flume.waves.size() > 16)
    throw Error(kSubject, fmt::format("PorousLayerFlume::waves holds {} waves", flume.waves.size()), "give 1 to 16 waves");
  double height_sum_m = 0.0, longest_period_s = 0.0;
  for (const FlumeWave& wave : flume.waves) {
    check("waves[].period_s", wave.period_s, 0.2, 60.0, "wind waves and swell");
    check("waves[].height_m", wave.height_m, 1e-4, 0.6 * flume.still_water_depth_m, "below breaking, 0.6 d");
    height_sum_m += wave.height_m;
    longest_period_s = std::max(longest_period_s, wave.period_s);
  }
  check("sum of waves[].height_m", height_sum_m, 0.0, 0.8 * flume.still_water_depth_m, "their crests together below 0.8 d");
  check("spacing_m", flume.spacing_m, 1e-3, 1000.0, "a cell size");
  check("layer_width_m", flume.layer_width_m, 0.5 * flume.spacing_m, 5000.0, "at least one cell");
  if (!(porosity > kWallPorosity && porosity <= 1.0))
    throw Error(kSubject, fmt::format("porosity {} is outside ({} .. 1]", porosity, kWallPorosity),
                "a porosity at or below kWallPorosity is a wall, not a layer");
  const double depth_m = flume.solver.effective_depth_limit_m > 0.0 ? std::min(flume.still_water_depth_m, flume.solver.effective_depth_limit_m)
                                                                     : flume.still_water_depth_m;
  // The common record: one wave's period for a regular wave, else eight of the longest periods;
  // each frequency moved to a whole number of cycles in it (by at most 1/16 of a cycle per period
  // of the longest: 6 %), kept distinct.
  const double record_s = flume.waves.size() == 1 ? flume.waves.front().period_s : 8.0 * longest_period_s;
  std::vector<double> w;
  for (const FlumeWave& wave : flume.waves) {
    double cycles = std::max(1.0, std::round(record_s / wave.period_s));
    while (std::find(w.begin(), w.end(), 2.0 * kPi * cycles / record_s) != w.end()) cycles += 1.0;
    w.push_back(2.0 * kPi * cycles / record_s);
  }
  std::vector<double> k;
  for (double omega : w) k.push_back(boussinesq_wavenumber(omega, depth_m, flume.solver.dispersion_coefficient));
  // The wavenumber the discrete scheme carries, for the separation (whose error grows with
  // (k_true - k_used) times the gauges' span): centred differences see 2 sin(k dx / 2) / dx where the
  // equations have k, and Crank-Nicolson 2 tan(w dt / 2) / dt where they have w, so the scheme's
  // wave solves the model's dispersion relation with those in place of k and w (second order: at 8
  // cells per wavelength k is 2.6 % shorter than the model's).
  const auto scheme_wavenumber = [&](double omega, double dt) {
    const double omega_scheme = 2.0 / dt * std::tan(0.5 * omega * dt);
    const double k_model = boussinesq_wavenumber(omega_scheme, depth_m, flume.solver.dispersion_coefficient);
    const double half = 0.5 * k_model * flume.spacing_m;
    return half < 1.0 ? 2.0 / flume.spacing_m * std::asin(half) : k_model;
  };
  const double longest_wavelength_m = 2.0 * kPi / *std::min_element(k.begin(), k.end());
  const double L = longest_wavelength_m, dx = flume.spacing_m;
  const int layer_cells = std::max(1, static_cast<int>(std::lround(flume.layer_width_m / dx)));

  // Layout (header): lengths in metres, rounded to whole cells; the gauges span 0.4 of the longest
  // wave, which keeps every wave's spacings off multiples of its half wavelength.
  auto cells_of = [dx](double length_m) { return static_cast<int>(std::ceil(length_m / dx)); };
  const double west_sponge_m = std::max(1.5 * L, 8.0 * dx);
  const double source_m = west_sponge_m + std::max(L, 6.0 * dx);
  const double gauges_m = source_m + std::max(0.8 * L, 4.0 * dx);
  const double shortest_wavelength_m = 2.0 * kPi / *std::max_element(k.begin(), k.end());
  const std::vector<int> front_gauges = gauge_cells(gauges_m, shortest_wavelength_m, L, dx);
  // The gauges close to the layer (0.3 L): what the scheme damps on the way (the grid-scale filter
  // on coarse cells) then takes little off the reflected wave before it is measured.
  const int layer_first = front_gauges.back() + 1 + cells_of(std::max(0.3 * L, 3.0 * dx));
  const int layer_last = layer_first + layer_cells - 1;
  std::vector<int> back_gauges;
  // The wall behind the layer is laid as the bake lays a structure's core: cells of porosity 0
  // inside the grid, not the grid's own edge. The two are different walls to the scheme above
  // k h ~ 1.5 (an interior wall's neighbours lose the dispersive terms the edge's mirror keeps:
  // docs/solver.md "Walls and the dispersive terms"), and a layer in front of one resonates differently: at 5 s over 12 m
  // on 3 m cells a nine-cell layer fitted against the edge to Kr 0.49 reflected 0.59 in the bake.
  const int wall_cells = flume.wall_behind ? kWallCells : 0;
  int columns = layer_last + 1 + wall_cells;
  double east_sponge_m = 0.0;
  if (!flume.wall_behind) {
    back_gauges = gauge_cells((layer_last + 1) * dx + std::max(0.8 * L, 4.0 * dx), shortest_wavelength_m, L, dx);
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
  for (int c = layer_last + 1; c <= layer_last + wall_cells; ++c) harbour.porosity(c, 0) = 0.0f;

  SolverParameters parameters = flume.solver;
  parameters.breaking.enabled = false;
  parameters.sponges = {{Side::kWest, west_sponge_m}};
  if (!flume.wall_behind) parameters.sponges.push_back({Side::kEast, east_sponge_m});
  // A whole number of steps per record (Courant <= 0.5): the harmonic analysis is then exact.
  const double courant_dt = 0.5 * dx / std::sqrt(ocean::kGravity_m_s2 * flume.still_water_depth_m);
  const int steps_per_record = std::max(8, static_cast<int>(std::ceil(record_s / courant_dt)));
  parameters.time_step_s = record_s / steps_per_record;
  std::vector<double> k_scheme;
  for (double omega : w) k_scheme.push_back(scheme_wavenumber(omega, parameters.time_step_s));
  WaveMaker maker;
  maker.kind = WaveMaker::Kind::kComponents;
  // Phases spread by the golden angle, so several waves never all crest together.
  for (std::size_t i = 0; i < flume.waves.size(); ++i)
    maker.sea_state.components.push_back({0.5 * flume.waves[i].height_m, w[i], 0.0, 2.399963 * static_cast<double>(i)});
  maker.source_line_m = source_m;
  maker.facing = Side::kWest;
  maker.ramp_time_s = 2.0 * longest_period_s;
  BoussinesqSolver solver(harbour, parameters, maker);

  // Steady once the front (group speed of the slowest wave) has gone source -> east end -> back
  // past the front gauges (two crossings; the source line lets the reflected wave through to the
  // west sponge, so nothing comes back a second time but the sponge's per cent), with half a
  // crossing and the ramp to spare.
  double slowest_m_s = INFINITY;
  for (double wavenumber : k) slowest_m_s = std::min(slowest_m_s, ocean::group_speed_m_s(wavenumber, depth_m));
  const double crossing_s = (columns * dx - source_m) / slowest_m_s;
  const int spin_up_records = static_cast<int>(std::ceil((3.0 * longest_period_s + 2.5 * crossing_s) / record_s));
  const int record_count = flume.waves.size() == 1 ? 4 : 1;
  const long first_step = static_cast<long>(spin_up_records) * steps_per_record;
  const long last_step = first_step + static_cast<long>(record_count) * steps_per_record;
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
  auto separate = [&](std::size_t first, std::size_t count, std::size_t wave) {
    std::vector<double> positions;
    std::vector<std::complex<double>> amplitudes;
    for (std::size_t g = first; g < first + count; ++g) {
      positions.push_back(geometry.cell_centre_x_m(all_gauges[g]));
      amplitudes.push_back(harmonic_amplitude(records[g], (first_step + 1) * parameters.time_step_s, parameters.time_step_s, w[wave]));
    }
    return separate_incident_reflected(positions, amplitudes, k_scheme[wave]);
  };
  LayerResponse response;
  response.porosity = porosity;
  response.stone_diameter_m = parameters.porous.stone_diameter_m;
  double incident_m2 = 0.0, reflected_m2 = 0.0, transmitted_m2 = 0.0;
  for (std::size_t i = 0; i < flume.waves.size(); ++i) {
    const IncidentReflected front = separate(0, front_gauges.size(), i);
    LayerResponse own;
    own.porosity = porosity;
    own.stone_diameter_m = response.stone_diameter_m;
    own.reflection_coefficient = front.reflection_coefficient();
    own.relative_depth_kh = k[i] * depth_m;
    own.layer_width_wavelengths = layer_cells * dx * k[i] / (2.0 * kPi);
    own.period_s = 2.0 * kPi / w[i];
    incident_m2 += std::norm(front.incident);
    reflected_m2 += std::norm(front.reflected);
    if (!flume.wall_behind) {
      const IncidentReflected back = separate(front_gauges.size(), back_gauges.size(), i);
      own.transmission_coefficient = std::abs(back.incident) / std::abs(front.incident);
      transmitted_m2 += std::norm(back.incident);
    }
    response.per_wave.push_back(own);
  }
  const LayerResponse& middle = response.per_wave[response.per_wave.size() / 2];
  response.reflection_coefficient = std::sqrt(reflected_m2 / incident_m2);
  response.transmission_coefficient = std::sqrt(transmitted_m2 / incident_m2);
  response.relative_depth_kh = middle.relative_depth_kh;
  response.layer_width_wavelengths = middle.layer_width_wavelengths;
  response.period_s = middle.period_s;
  if (flume.waves.size() == 1) response.per_wave.clear();
  return response;
}

namespace {

// Regula falsi (Illinois variant) on n between `low` and `high`, whose values straddle `target`;
// value(n) monotone on the interval. Converges in a few runs where bisection would take six.
template <typename Measure, typename Value>
PorosityFit regula_falsi(Measure&& measure, double target, double tolerance, LayerResponse low, LayerResponse high, Value&& value,
                         int runs) {
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
    const LayerResponse middle = measure(n);
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
  // The chart of Kr against n, walked from open (Kr -> 1, the wall alone) towards nearly
  // closed (Kr -> 1 again, the layer itself a wall) until it brackets the request or turns up past
  // its minimum; the branch above the minimum is the one fitted.
  // n = 1 first: the faces open, the wall alone (its own reflection, less than 1 by the bed friction
  // and the scheme on the way).
  // Kr is the layer's: relative to what the wall alone returns in the same flume (n = 1), so the
  // bed friction on the way (strong in shallow water) is not counted against the layer.
  const double chart_porosity[] = {0.9, 0.75, 0.6, 0.42, 0.28, 0.17, kLowestFittedPorosity};
  const LayerResponse wall = measure_porous_layer(flume, 1.0);
  auto relative = [&](const LayerResponse& r) { return relative_to(wall, &LayerResponse::reflection_coefficient, r); };
  auto measure = [&](double n) { return relative(measure_porous_layer(flume, n)); };
  std::vector<LayerResponse> chart = {relative(wall)};
  auto kr = [](const LayerResponse& r) { return r.reflection_coefficient; };
  for (double n : chart_porosity) {
    chart.push_back(measure(n));
    const int runs = static_cast<int>(chart.size());
    const LayerResponse& last = chart.back();
    if (runs == 1) {
      if (reflection_coefficient >= kr(last) - tolerance) return {last, reflection_coefficient <= kr(last) + tolerance, runs};
      continue;
    }
    const LayerResponse& before = chart[chart.size() - 2];
    if (kr(last) <= reflection_coefficient) return regula_falsi(measure, reflection_coefficient, tolerance, last, before, kr, runs);
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
    const LayerResponse between = measure(0.5 * (chart[neighbour].porosity + lowest->porosity));
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
  // Kt is the layer's: the transmitted height over what the same flume carries without it (n = 1),
  // so the bed friction and the scheme on the way (strong in shallow water) are not counted.
  const LayerResponse without = measure_porous_layer(flume, 1.0);
  auto relative = [&](const LayerResponse& r) { return relative_to(without, &LayerResponse::transmission_coefficient, r); };
  auto measure = [&](double n) { return relative(measure_porous_layer(flume, n)); };
  const LayerResponse closed = measure(kLowestFittedPorosity);
  const LayerResponse open = measure(0.98);
  auto kt = [](const LayerResponse& r) { return r.transmission_coefficient; };
  if (transmission_coefficient <= closed.transmission_coefficient + tolerance)
    return {closed, transmission_coefficient >= closed.transmission_coefficient - tolerance, 3};
  if (transmission_coefficient >= open.transmission_coefficient - tolerance)
    return {open, transmission_coefficient <= open.transmission_coefficient + tolerance, 3};
  return regula_falsi(measure, transmission_coefficient, tolerance, closed, open, kt, 3);
}

}  // namespace nearshore::boussinesq
