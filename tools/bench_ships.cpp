// `nearshore bench ships`: the flags of the per-ship cost benchmark (bench/ships_bench.hpp;
// docs/ships.md, issue 18).
#include <cstdio>
#include <memory>

#include "command_support.hpp"
#include "nearshore/bench/ships_bench.hpp"

namespace nearshore::tools {

void add_bench_ships(CLI::App& bench) {
  struct Options {
    bench::ShipsBenchOptions measure;
    bool json = false;
  };
  auto o = std::make_shared<Options>();
  bench::ShipsBenchOptions& m = o->measure;
  CLI::App* command = bench.add_subcommand("ships", "Per-ship cost of the rigid body and of a bow-wave step, one core");
  command->add_option("--points", m.hull_points, "Hull feature points of the rigid body")->check(number_in(at_least(16), at_most(1e6)));
  // At least 32: the dispersive wake layer the bench also steps needs 32 cells a side.
  command->add_option("--grid", m.grid_cells, "Cells per side of the shallow-water grid")->check(number_in(at_least(32), at_most(2048)));
  command->add_option("--repeats", m.repeats, "Timed repetitions (the median is reported)")->check(number_in(at_least(1), at_most(1e6)));
  command->add_option("--beaufort", m.beaufort, "Beaufort force of the deep sea the hull samples (1-12)")->check(number_in(at_least(1), at_most(12)));
  command->add_option("--fleet", m.fleet_ships, "Ships of the fleet stepped together at 30 Hz (0: no fleet line)")
      ->check(number_in(at_least(0), at_most(64)));
  command->add_flag("--dispersive-wake,!--no-dispersive-wake", m.dispersive_wake,
                   "Give the fleet's ships the dispersive (Kelvin) wake layer too (the default; --no-dispersive-wake: "
                   "the bow-wave grid alone); below depth Froude number 0.7 it is shown and stepped instead of the grid");
  command->add_flag("--json", o->json, "Print the results as JSON");
  set_example(*command, "nearshore bench ships --points 1000 --grid 256 --fleet 8");
  command->callback([o]() {
    const bench::ShipsBenchResult result = bench::run_ships_bench(o->measure);
    if (o->json)
      std::puts(bench::ships_bench_json(result).dump(2).c_str());
    else
      std::fputs(bench::ships_bench_text(result).c_str(), stdout);
  });
}

}  // namespace nearshore::tools
