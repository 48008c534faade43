// `nearshore bench ships`: what one ship costs a host per frame, on one core (docs/ships.md,
// issue 18):
//  1. the rigid body: one 1/60 s substep of a hull of --points feature points (a 24 x 9 x 4.5 m
//     box barge at 3 m draft: its 12 faces sample to the count asked; the lofted tug has more faces),
//     on a Beaufort --beaufort deep sea through the runtime's CPU queries, and in still water
//     (the difference is the surface queries' share);
//  2. one Kurganov-Petrova step (SSP-RK2, two stages) on a --grid x --grid shallow-water grid, in
//     float (the bow waves' precision) and in double (the reference), and one bow-wave update per 30 Hz frame (forcing, the steps the CFL limit asks for,
//     absorbing layer, heights) of the tug at 3 m/s over 10 m of water;
//  3. one step of the dispersive wake layer (dispersive_wake.hpp) on --grid x --grid nodes: two
//     forward and two inverse float FFTs, the exact rotation of every mode, the absorbing layer and
//     the drawn heights.
//  4. a fleet (issue 42: eight ships at 30 Hz on one core): --fleet ships as a host would make them
//     (ShipFleet, every default: bow-wave grid, stern wake, restricted water; tugs, Wigley launches and
//     barges in turn, 150 m apart, ordered ahead at 3 m/s) on the same Beaufort sea, one 30 Hz
//     frame (fleet.step) at a time; the whole frame's CPU time against the frame's 33.3 ms.
//     --dispersive-wake gives every ship the dispersive layer too (ShipDefinition::dispersive_wake):
//     with no seabed each is at Fr_d 0.07 and shows that layer alone (ship_fleet.hpp WakeLayerChoice).
// CPU time of the calling thread, median (and fastest) of --repeats; the load average is printed with it.
// Everything runs on the calling thread: the ships' code uses no worker threads.
#include <time.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "command_support.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/runtime/deep_water_source.hpp"
#include "nearshore/runtime/surface_sampler.hpp"
#include "nearshore/ships/bow_wave.hpp"
#include "nearshore/ships/dispersive_wake.hpp"
#include "nearshore/ships/generic_hulls.hpp"
#include "nearshore/ships/shallow_water.hpp"
#include "nearshore/ships/ship_body.hpp"
#include "nearshore/ships/ship_fleet.hpp"

namespace nearshore::tools {
namespace {

// Median and fastest of `repeats` timings (ms). On a shared machine the CPU time of a thread also
// counts what a sibling hyperthread or the host takes from it, so the median is what a loaded
// frame costs and the fastest repeat is close to the uncontended cost; both are reported.
struct Timing {
  double median_ms = 0.0, fastest_ms = 0.0;
};

template <class F>
Timing time_ms(int repeats, F&& f) {
  std::vector<double> ms;
  for (int k = 0; k < repeats; ++k) {
    const double start = thread_cpu_s();
    f();
    ms.push_back(1e3 * (thread_cpu_s() - start));
  }
  std::nth_element(ms.begin(), ms.begin() + ms.size() / 2, ms.end());
  return {ms[ms.size() / 2], *std::min_element(ms.begin(), ms.end())};
}

struct ShipsBenchOptions {
  int points = 1000, grid = 256, repeats = 200, beaufort = 5, fleet = 8;
  bool json = false;
  bool dispersive_wake = false;
};

}  // namespace

void add_bench_ships(CLI::App& bench) {
  auto o = std::make_shared<ShipsBenchOptions>();
  CLI::App* command = bench.add_subcommand("ships", "Per-ship cost of the rigid body and of a bow-wave step, one core");
  command->add_option("--points", o->points, "Hull feature points of the rigid body")->check(number_in(at_least(16), at_most(1e6)));
  command->add_option("--grid", o->grid, "Cells per side of the shallow-water grid")->check(number_in(at_least(16), at_most(2048)));
  command->add_option("--repeats", o->repeats, "Timed repetitions (the median is reported)")->check(number_in(at_least(1), at_most(1e6)));
  command->add_option("--beaufort", o->beaufort, "Beaufort force of the deep sea the hull samples (1-12)")->check(number_in(at_least(1), at_most(12)));
  command->add_option("--fleet", o->fleet, "Ships of the fleet stepped together at 30 Hz (0: no fleet line)")
      ->check(number_in(at_least(0), at_most(64)));
  command->add_flag("--dispersive-wake", o->dispersive_wake,
                   "Give the fleet's ships the dispersive (Kelvin) wake layer too; below depth Froude number 0.7 it is "
                   "shown and stepped instead of the bow-wave grid");
  command->add_flag("--json", o->json, "Print the results as JSON");
  set_example(*command, "nearshore bench ships --points 1000 --grid 256 --fleet 8");
  command->callback([o]() {
    // 1. Rigid body.
    const ships::HullMesh hull = ships::box_barge(24.0, 9.0, 4.5);
    ships::HullSamples samples = ships::sample_hull(hull, o->points);
    const ships::HullSamples tug_samples = ships::sample_hull(ships::harbour_tug(), o->points);
    ships::HullLoading loading;
    loading.draft_m = 3.0;
    const ships::ShipParticulars particulars = ships::particulars_for_hull("bench barge", hull, samples, loading);
    const ships::ShipParticulars tug = ships::particulars_for_hull("bench tug", ships::harbour_tug(), tug_samples, loading);
    const int point_count = static_cast<int>(samples.size());
    ships::ShipState state;
    state.position_m = {500.0, 500.0, particulars.centre_of_gravity_m.z() - particulars.design_draft_m};
    state.velocity_m_s = {3.0, 0.0, 0.0};
    ships::ShipBody body(samples, particulars, state);

    runtime::BeaufortSea sea;
    sea.force = o->beaufort;
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
    const double body_sea_ms = time_ms(o->repeats, [&] { body.step(at_sea, controls, {}, substep_s); }).median_ms;
    const double body_still_ms = time_ms(o->repeats, [&] { body.step(still, controls, {}, substep_s); }).median_ms;

    // 2. Shallow water: one SSP-RK2 step on grid x grid cells of 0.5 m over 10 m with a hump, in
    //    float (what bow waves run on) and in double (the reference).
    const int swe_repeats = std::max(5, o->repeats / 10);
    auto time_step = [&](auto grid) {
      for (int j = 0; j <= o->grid; ++j)
        for (int i = 0; i <= o->grid; ++i) grid.set_bottom_corner(i, j, -10.0);
      grid.update_bottom();
      for (int j = 0; j < o->grid; ++j)
        for (int i = 0; i < o->grid; ++i)
          grid.surface_m(i, j) = static_cast<typename decltype(grid)::Scalar>(
              0.3 * std::exp(-(std::pow(i - o->grid / 2.0, 2) + std::pow(j - o->grid / 2.0, 2)) / 50.0));
      const double dt = grid.stable_time_step_s();
      return time_ms(swe_repeats, [&] { grid.step(dt); });
    };
    const Timing swe_step = time_step(ships::BowWaveGrid(o->grid, o->grid, 0.5, ships::EdgeKind::kOpen));
    const Timing swe_step_double = time_step(ships::ShallowWaterGrid(o->grid, o->grid, 0.5, ships::EdgeKind::kOpen));

    // 3. The bow wave of the tug at 3 m/s, grid x grid cells over 4 ship lengths.
    ships::BowWaveOptions wave_options;
    wave_options.cells = o->grid;
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
    const Timing wave_frame = time_ms(swe_repeats, move);
    const double steps_per_frame = frames > 0 ? static_cast<double>(steps) / frames : 0.0;
    // 4. The dispersive wake layer: one step of 1/30 s over 50 m of water with a pressure patch.
    ships::DispersiveWakeOptions dispersive_options;
    dispersive_options.cells = o->grid;
    ships::DispersiveWake dispersive(0.4, dispersive_options);
    for (int j = 0; j < o->grid; ++j)
      for (int i = 0; i < o->grid; ++i)
        dispersive.pressure_head_m(i, j) = static_cast<float>(
            0.5 * std::exp(-(std::pow(i - o->grid / 2.0, 2) + std::pow(j - o->grid / 2.0, 2)) / 50.0));
    dispersive.advance(frame_s, 50.0);  // plans the rotation for this step and depth once
    const Timing dispersive_step = time_ms(swe_repeats, [&] { dispersive.advance(frame_s, 50.0); });

    // 5. The fleet: what a host's frame costs with --fleet ships, every default of ShipDefinition.
    ships::ShipFleet fleet;
    for (int k = 0; k < o->fleet; ++k) {
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
      ship.dispersive_wake = o->dispersive_wake;
      fleet.add_ship(ship);
    }
    Timing fleet_frame;
    if (o->fleet > 0) {
      for (int k = 0; k < 30; ++k) fleet.step(&water, frame_s);  // the bow waves' start-up
      fleet_frame = time_ms(swe_repeats, [&] { fleet.step(&water, frame_s); });
    }
    const std::string load = proc_loadavg_line();

    if (o->json) {
      nlohmann::json j = {{"hull_points", point_count},
                          {"rigid_body_substep_ms_at_sea", body_sea_ms},
                          {"rigid_body_substep_ms_still_water", body_still_ms},
                          {"beaufort", o->beaufort},
                          {"grid", o->grid},
                          {"shallow_water_step_ms", swe_step.median_ms},
                          {"shallow_water_step_fastest_ms", swe_step.fastest_ms},
                          {"shallow_water_step_double_ms", swe_step_double.median_ms},
                          {"bow_wave_update_ms_per_30hz_frame", wave_frame.median_ms},
                          {"bow_wave_update_fastest_ms", wave_frame.fastest_ms},
                          {"bow_wave_steps_per_frame", steps_per_frame},
                          {"bow_wave_spacing_m", wave.field().spacing_m},
                          {"dispersive_wake_step_ms", dispersive_step.median_ms},
                          {"dispersive_wake_step_fastest_ms", dispersive_step.fastest_ms},
                          {"fleet_ships", o->fleet},
                          {"fleet_dispersive_wake", o->dispersive_wake},
                          {"fleet_frame_ms", fleet_frame.median_ms},
                          {"fleet_frame_fastest_ms", fleet_frame.fastest_ms},
                          {"fleet_frame_budget_ms", 1e3 * frame_s},
                          {"load_average", load}};
      std::puts(j.dump(2).c_str());
      return;
    }
    std::printf("nearshore bench ships: one core (CPU time of this thread, median of %d)\n", o->repeats);
    std::printf("  rigid body (box barge), %d hull points, one 1/60 s substep: %.3f ms on a Beaufort %d sea (runtime queries), "
                "%.3f ms in still water\n",
                point_count, body_sea_ms, o->beaufort, body_still_ms);
    std::printf("  shallow water, %d x %d cells, one SSP-RK2 step (2 stages): %.3f ms in float (bow waves; fastest %.3f ms), "
                "%.3f ms in double\n",
                o->grid, o->grid, swe_step.median_ms, swe_step.fastest_ms, swe_step_double.median_ms);
    std::printf("  bow wave of a 24 m tug at 3 m/s, %d x %d cells of %.2f m over 10 m: %.3f ms per 30 Hz frame "
                "(fastest %.3f ms; %.2f steps per frame)\n",
                o->grid, o->grid, wave.field().spacing_m, wave_frame.median_ms, wave_frame.fastest_ms, steps_per_frame);
    std::printf("  dispersive wake layer, %d x %d nodes, one step (4 float FFTs, rotation, absorbing layer, heights): "
                "%.3f ms (fastest %.3f ms)\n",
                o->grid, o->grid, dispersive_step.median_ms, dispersive_step.fastest_ms);
    if (o->fleet > 0)
      std::printf("  a fleet of %d ships (tugs, launches, barges; every default: bow-wave grid, stern wake, restricted water%s) at "
                  "3 m/s on the Beaufort %d sea, one 30 Hz frame: %.3f ms (fastest %.3f ms) of the frame's %.1f ms\n",
                  o->fleet, o->dispersive_wake ? "; and the dispersive wake layer, shown instead of the grid" : "",
                  o->beaufort, fleet_frame.median_ms, fleet_frame.fastest_ms, 1e3 * frame_s);
    std::printf("  load average (/proc/loadavg): %s\n", load.c_str());
  });
}

}  // namespace nearshore::tools
