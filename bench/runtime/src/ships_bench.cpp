#include "nearshore/bench/ships_bench.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <fmt/format.h>
#include <fmt/printf.h>

#include "nearshore/core/process_usage.hpp"
#include "nearshore/runtime/deep_water_source.hpp"
#include "nearshore/runtime/surface_sampler.hpp"
#include "nearshore/ships/bow_wave.hpp"
#include "nearshore/ships/dispersive_wake.hpp"
#include "nearshore/ships/generic_hulls.hpp"
#include "nearshore/ships/shallow_water.hpp"
#include "nearshore/ships/ship_body.hpp"
#include "nearshore/ships/ship_fleet.hpp"

namespace nearshore::bench {
namespace {

template <class F>
CpuTiming time_ms(int repeats, F&& f) {
  std::vector<double> ms;
  for (int k = 0; k < repeats; ++k) {
    const double start = thread_cpu_s();
    f();
    ms.push_back(1e3 * (thread_cpu_s() - start));
  }
  std::nth_element(ms.begin(), ms.begin() + ms.size() / 2, ms.end());
  return {ms[ms.size() / 2], *std::min_element(ms.begin(), ms.end())};
}

}  // namespace

ShipsBenchResult run_ships_bench(const ShipsBenchOptions& o) {
  ShipsBenchResult result;
  result.options = o;
  // 1. Rigid body.
  const ships::HullMesh hull = ships::box_barge(24.0, 9.0, 4.5);
  ships::HullSamples samples = ships::sample_hull(hull, o.hull_points);
  const ships::HullSamples tug_samples = ships::sample_hull(ships::harbour_tug(), o.hull_points);
  ships::HullLoading loading;
  loading.draft_m = 3.0;
  const ships::ShipParticulars particulars = ships::particulars_for_hull("bench barge", hull, samples, loading);
  const ships::ShipParticulars tug = ships::particulars_for_hull("bench tug", ships::harbour_tug(), tug_samples, loading);
  result.hull_points = static_cast<int>(samples.size());
  ships::ShipState state;
  state.position_m = {500.0, 500.0, particulars.centre_of_gravity_m.z() - particulars.design_draft_m};
  state.velocity_m_s = {3.0, 0.0, 0.0};
  ships::ShipBody body(samples, particulars, state);

  runtime::BeaufortSea sea;
  sea.force = o.beaufort;
  const std::unique_ptr<ocean::DeepWaterField> field = runtime::build_beaufort_field(sea);
  field->synthesise(10.0);
  auto keyframe = std::make_shared<runtime::DeepWaterKeyframe>();
  for (int c = 0; c < field->cascade_count(); ++c) keyframe->cascades.push_back(field->frame(c));
  runtime::SurfaceSnapshot snapshot;
  snapshot.deep_from = snapshot.deep_to = keyframe;
  const runtime::SurfaceSampler water(snapshot);
  ships::ShipEnvironment at_sea, still;
  at_sea.water = &water;
  const ships::ShipControls controls{0.5, 0.1};
  const double substep_s = 1.0 / 60.0;
  body.step(at_sea, controls, {}, substep_s);
  result.rigid_body_substep_ms_at_sea = time_ms(o.repeats, [&] { body.step(at_sea, controls, {}, substep_s); }).median_ms;
  result.rigid_body_substep_ms_still_water = time_ms(o.repeats, [&] { body.step(still, controls, {}, substep_s); }).median_ms;

  // 2. Shallow water: one SSP-RK2 step on grid x grid cells of 0.5 m over 10 m with a hump, in
  //    float (what bow waves run on) and in double (the reference).
  const int swe_repeats = std::max(5, o.repeats / 10);
  auto time_step = [&](auto grid) {
    for (int j = 0; j <= o.grid_cells; ++j)
      for (int i = 0; i <= o.grid_cells; ++i) grid.set_bottom_corner(i, j, -10.0);
    grid.update_bottom();
    for (int j = 0; j < o.grid_cells; ++j)
      for (int i = 0; i < o.grid_cells; ++i)
        grid.surface_m(i, j) = static_cast<typename decltype(grid)::Scalar>(
            0.3 * std::exp(-(std::pow(i - o.grid_cells / 2.0, 2) + std::pow(j - o.grid_cells / 2.0, 2)) / 50.0));
    const double dt = grid.stable_time_step_s();
    return time_ms(swe_repeats, [&] { grid.step(dt); });
  };
  result.shallow_water_step = time_step(ships::BowWaveGrid(o.grid_cells, o.grid_cells, 0.5, ships::EdgeKind::kOpen));
  result.shallow_water_step_double = time_step(ships::ShallowWaterGrid(o.grid_cells, o.grid_cells, 0.5, ships::EdgeKind::kOpen));

  // 3. The bow wave of the tug at 3 m/s, grid x grid cells over 4 ship lengths.
  ships::BowWaveOptions wave_options;
  wave_options.cells = o.grid_cells;
  ships::BowWave wave(tug, wave_options);
  ships::ShipState tug_state = state;
  tug_state.position_m.z() = tug.centre_of_gravity_m.z() - tug.design_draft_m;
  ships::ShipBody mover(tug_samples, tug, tug_state);
  const double frame_s = 1.0 / 30.0;
  int steps = 0, frames = 0;
  auto move = [&] {
    ships::ShipState s = mover.state();
    s.position_m.x() += 3.0 * frame_s;
    mover.set_state(s);
    wave.update(mover, nullptr, frame_s);
    steps += wave.last_steps();
    ++frames;
  };
  for (int k = 0; k < 30; ++k) move();  // leave the start-up behind
  steps = frames = 0;
  result.bow_wave_frame = time_ms(swe_repeats, move);
  result.bow_wave_steps_per_frame = frames > 0 ? static_cast<double>(steps) / frames : 0.0;
  result.bow_wave_spacing_m = wave.field().spacing_m;
  // 4. The dispersive wake layer: one step of 1/30 s over 50 m of water with a pressure patch.
  ships::DispersiveWakeOptions dispersive_options;
  dispersive_options.cells = o.grid_cells;
  ships::DispersiveWake dispersive(0.4, dispersive_options);
  for (int j = 0; j < o.grid_cells; ++j)
    for (int i = 0; i < o.grid_cells; ++i)
      dispersive.pressure_head_m(i, j) = static_cast<float>(
          0.5 * std::exp(-(std::pow(i - o.grid_cells / 2.0, 2) + std::pow(j - o.grid_cells / 2.0, 2)) / 50.0));
  dispersive.advance(frame_s, 50.0);  // plans the rotation for this step and depth once
  result.dispersive_wake_step = time_ms(swe_repeats, [&] { dispersive.advance(frame_s, 50.0); });

  // 5. The fleet: what a host's frame costs with fleet_ships ships, every default of ShipDefinition.
  ships::ShipFleet fleet;
  for (int k = 0; k < o.fleet_ships; ++k) {
    ships::ShipDefinition ship;
    ship.name = fmt::format("ship {}", k + 1);
    switch (k % 3) {
      case 0: ship.hull = ships::harbour_tug(); ship.loading.draft_m = 3.0; break;
      case 1: ship.hull = ships::wigley_hull(12.0, 3.0, 0.9, 2.0); ship.loading.draft_m = 0.9; break;
      default: ship.hull = ships::box_barge(24.0, 9.0, 4.5); ship.loading.draft_m = 3.0; break;
    }
    ship.x_m = 150.0 * (k % 4);
    ship.y_m = 150.0 * (k / 4);
    ship.initial_speed_m_s = 3.0;
    ship.orders.speed_m_s = 3.0;
    ship.dispersive_wake = o.dispersive_wake;
    fleet.add_ship(ship);
  }
  if (o.fleet_ships > 0) {
    for (int k = 0; k < 30; ++k) fleet.step(&water, frame_s);  // the bow waves' start-up
    result.fleet_frame = time_ms(swe_repeats, [&] { fleet.step(&water, frame_s); });
  }
  result.frame_budget_ms = 1e3 * frame_s;
  result.load_average = proc_loadavg_line();
  return result;
}

nlohmann::json ships_bench_json(const ShipsBenchResult& r) {
  return {{"hull_points", r.hull_points},
          {"rigid_body_substep_ms_at_sea", r.rigid_body_substep_ms_at_sea},
          {"rigid_body_substep_ms_still_water", r.rigid_body_substep_ms_still_water},
          {"beaufort", r.options.beaufort},
          {"grid", r.options.grid_cells},
          {"shallow_water_step_ms", r.shallow_water_step.median_ms},
          {"shallow_water_step_fastest_ms", r.shallow_water_step.fastest_ms},
          {"shallow_water_step_double_ms", r.shallow_water_step_double.median_ms},
          {"bow_wave_update_ms_per_30hz_frame", r.bow_wave_frame.median_ms},
          {"bow_wave_update_fastest_ms", r.bow_wave_frame.fastest_ms},
          {"bow_wave_steps_per_frame", r.bow_wave_steps_per_frame},
          {"bow_wave_spacing_m", r.bow_wave_spacing_m},
          {"dispersive_wake_step_ms", r.dispersive_wake_step.median_ms},
          {"dispersive_wake_step_fastest_ms", r.dispersive_wake_step.fastest_ms},
          {"fleet_ships", r.options.fleet_ships},
          {"fleet_dispersive_wake", r.options.dispersive_wake},
          {"fleet_frame_ms", r.fleet_frame.median_ms},
          {"fleet_frame_fastest_ms", r.fleet_frame.fastest_ms},
          {"fleet_frame_budget_ms", r.frame_budget_ms},
          {"load_average", r.load_average}};
}

std::string ships_bench_text(const ShipsBenchResult& r) {
  const ShipsBenchOptions& o = r.options;
  std::string text = fmt::sprintf("nearshore bench ships: one core (CPU time of this thread, median of %d)\n", o.repeats);
  text += fmt::sprintf("  rigid body (box barge), %d hull points, one 1/60 s substep: %.3f ms on a Beaufort %d sea (runtime queries), "
                       "%.3f ms in still water\n",
                       r.hull_points, r.rigid_body_substep_ms_at_sea, o.beaufort, r.rigid_body_substep_ms_still_water);
  text += fmt::sprintf("  shallow water, %d x %d cells, one SSP-RK2 step (2 stages): %.3f ms in float (bow waves; fastest %.3f ms), "
                       "%.3f ms in double\n",
                       o.grid_cells, o.grid_cells, r.shallow_water_step.median_ms, r.shallow_water_step.fastest_ms,
                       r.shallow_water_step_double.median_ms);
  text += fmt::sprintf("  bow wave of a 24 m tug at 3 m/s, %d x %d cells of %.2f m over 10 m: %.3f ms per 30 Hz frame "
                       "(fastest %.3f ms; %.2f steps per frame)\n",
                       o.grid_cells, o.grid_cells, r.bow_wave_spacing_m, r.bow_wave_frame.median_ms,
                       r.bow_wave_frame.fastest_ms, r.bow_wave_steps_per_frame);
  text += fmt::sprintf("  dispersive wake layer, %d x %d nodes, one step (4 float FFTs, rotation, absorbing layer, heights): "
                       "%.3f ms (fastest %.3f ms)\n",
                       o.grid_cells, o.grid_cells, r.dispersive_wake_step.median_ms, r.dispersive_wake_step.fastest_ms);
  if (o.fleet_ships > 0)
    text += fmt::sprintf("  a fleet of %d ships (tugs, launches, barges; every default: bow-wave grid, stern wake, restricted water%s) at "
                         "3 m/s on the Beaufort %d sea, one 30 Hz frame: %.3f ms (fastest %.3f ms) of the frame's %.1f ms\n",
                         o.fleet_ships, o.dispersive_wake ? "; and the dispersive wake layer, shown instead of the grid" : "",
                         o.beaufort, r.fleet_frame.median_ms, r.fleet_frame.fastest_ms, r.frame_budget_ms);
  text += fmt::sprintf("  load average (/proc/loadavg): %s\n", r.load_average);
  return text;
}

}  // namespace nearshore::bench
