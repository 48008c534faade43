#pragma once
// `nearshore bench ships` (runtime side: ships/ on the runtime's queries; never the bake side): what
// one ship costs a host per frame, on one core (docs/ships.md, issue 18):
//  1. the rigid body: one 1/60 s substep of a hull of `hull_points` feature points (a 24 x 9 x 4.5 m
//     box barge at 3 m draft: its 12 faces sample to the count asked; the lofted tug has more faces),
//     on a Beaufort `beaufort` deep sea through the runtime's CPU queries, and in still water
//     (the difference is the surface queries' share);
//  2. one Kurganov-Petrova step (SSP-RK2, two stages) on a `grid_cells` x `grid_cells` shallow-water
//     grid, in float (the bow waves' precision) and in double (the reference), and one bow-wave
//     update per 30 Hz frame (forcing, the steps the CFL limit asks for, absorbing layer, heights) of
//     the tug at 3 m/s over 10 m of water;
//  3. one step of the dispersive wake layer (dispersive_wake.hpp) on grid_cells x grid_cells nodes:
//     two forward and two inverse float FFTs, the exact rotation of every mode, the absorbing layer
//     and the drawn heights.
//  4. a fleet (issue 42: eight ships at 30 Hz on one core): `fleet_ships` ships as a host would make
//     them (ShipFleet, every default: bow-wave grid, stern wake, restricted water; tugs, Wigley
//     launches and barges in turn, 150 m apart, ordered ahead at 3 m/s) on the same Beaufort sea,
//     one 30 Hz frame (fleet.step) at a time; the whole frame's CPU time against the frame's 33.3 ms.
//     `dispersive_wake` (ShipDefinition's default, on) gives every ship the dispersive layer too,
//     forced by its thin-ship sources: with no seabed each is at Fr_d 0.07 and, its 3 m/s waves
//     resolved by every hull's window, shows that layer alone (ship_fleet.hpp WakeLayerChoice).
// CPU time of the calling thread, median (and fastest) of `repeats`; the load average is reported
// with it. Everything runs on the calling thread: the ships' code uses no worker threads.
#include <string>

#include <nlohmann/json.hpp>

namespace nearshore::bench {

struct ShipsBenchOptions {
  int hull_points = 1000;  ///< hull feature points of the rigid body
  int grid_cells = 256;    ///< cells per side of the shallow-water grid (and nodes of the dispersive layer)
  int repeats = 200;       ///< timed repetitions of the rigid body (a tenth, at least 5, of the grids)
  int beaufort = 5;        ///< Beaufort force of the deep sea the hull samples (1-12)
  int fleet_ships = 8;     ///< ships of the fleet stepped together at 30 Hz (0: no fleet)
  bool dispersive_wake = true;  ///< the fleet's ships with the dispersive wake layer (the default)
};

/// Median and fastest of a number of timings (ms). On a shared machine the CPU time of a thread also
/// counts what a sibling hyperthread or the host takes from it, so the median is what a loaded frame
/// costs and the fastest repeat is close to the uncontended cost; both are reported.
struct CpuTiming {
  double median_ms = 0.0, fastest_ms = 0.0;
};

struct ShipsBenchResult {
  ShipsBenchOptions options;
  int hull_points = 0;  ///< as sampled (sample_hull's count for the asked one)
  double rigid_body_substep_ms_at_sea = 0.0, rigid_body_substep_ms_still_water = 0.0;  ///< medians
  CpuTiming shallow_water_step, shallow_water_step_double, bow_wave_frame, dispersive_wake_step, fleet_frame;
  double bow_wave_steps_per_frame = 0.0, bow_wave_spacing_m = 0.0;
  double frame_budget_ms = 1e3 / 30.0;
  std::string load_average;  ///< /proc/loadavg after the measurements
};

ShipsBenchResult run_ships_bench(const ShipsBenchOptions& options);

nlohmann::json ships_bench_json(const ShipsBenchResult& result);
std::string ships_bench_text(const ShipsBenchResult& result);

}  // namespace nearshore::bench
