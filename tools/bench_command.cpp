#include "command_support.hpp"

namespace nearshore::tools {

// `nearshore bench <stage>`: each stage's flags in bench_<stage>.cpp, its measurement in bench/
// (nearshore/bench/<stage>_bench.hpp).
void add_bench_command(CLI::App& app) {
  CLI::App* bench = app.add_subcommand("bench", "Measure throughput of a stage and print a table");
  set_example(*bench, "nearshore bench bake");
  bench->require_subcommand(1);
  add_bench_bathy(*bench);
  add_bench_bake(*bench);
  add_bench_deepwater(*bench);
  add_bench_loops(*bench);
  add_bench_play(*bench);
  add_bench_library(*bench);
  add_bench_ships(*bench);
}

}  // namespace nearshore::tools
