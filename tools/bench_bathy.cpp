// `nearshore bench bathy`: the flags of the gridding stage's benchmark (bench/bathy_bench.hpp).
#include <cstdio>

#include "command_support.hpp"
#include "nearshore/bench/bathy_bench.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/core/progress.hpp"

namespace nearshore::tools {

void add_bench_bathy(CLI::App& bench) {
  struct Options {
    bench::BathyBenchOptions measure;
    bool json = false;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = bench.add_subcommand("bathy", "Soundings/s triangulated and cells/s interpolated (Sibson) on a square grid");
  command->add_option("--grid", options->measure.grid_cells, "Cells per side of the square grid")
      ->check(number_in(at_least(2), at_most(100000)));
  command->add_option("--soundings", options->measure.soundings, "Scattered soundings to triangulate")
      ->check(number_in(at_least(3), at_most(1e9)));
  command->add_option("--spacing", options->measure.spacing_m, "Cell size in metres")
      ->check(number_in(above(0), at_most(100000)));
  command->add_flag("--json", options->json, "Print the results as JSON");
  set_example(*command, "nearshore bench bathy --grid 2000 --soundings 200000");
  command->callback(naming_flags_in_errors(
      {{"BathyBenchOptions::grid_cells", "--grid"},
       {"BathyBenchOptions::soundings", "--soundings"},
       {"BathyBenchOptions::spacing_m", "--spacing"}},
      [options]() {
        ProgressBar::set_quiet(options->json);
        const bench::BathyBenchResult result = bench::run_bathy_bench(options->measure);
        if (options->json)
          std::printf("%s\n", bench::bathy_bench_json(result).dump(2).c_str());
        else
          std::fputs(bench::bathy_bench_text(result).c_str(), stdout);
      }));
}

}  // namespace nearshore::tools
