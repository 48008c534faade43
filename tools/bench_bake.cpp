// `nearshore bench bake`: the flags of the whole-bake benchmark (bench/bake_bench.hpp);
// docs/commands/bench.md ("bench bake") shows the output.
#include <cstdio>
#include <memory>
#include <string>

#include <fmt/format.h>

#include "command_support.hpp"
#include "nearshore/bench/bake_bench.hpp"

namespace nearshore::tools {

void add_bench_bake(CLI::App& bench) {
  CLI::App* command = bench.add_subcommand(
      "bake", "Time whole bakes (run_bake on real case files, frames and gauges written): cell-updates/s per core "
              "(wall and CPU time), simulated s per wall s, peak memory, bytes per cell, a roofline line; each case with its "
              "own solver settings and in the seed configuration (weakly nonlinear, one ADI pass), side by side");
  set_example(*command, "nearshore bench bake --steps 200 --harbour-steps 10");
  struct Options {
    bench::BakeBenchOptions measure;
    std::string cases_folder = "data/cases", scratch;
    bool json = false;
  };
  auto options = std::make_shared<Options>();
  bench::BakeBenchOptions& m = options->measure;
  command->add_option("--steps", m.steps, "time steps of the Berkhoff and demo harbour bakes")
      ->capture_default_str()
      ->check(number_in(at_least(1), at_most(1000000)));
  command->add_option("--harbour-steps", m.harbour_steps, "time steps of the 1000 x 900 harbour bake")
      ->capture_default_str()
      ->check(number_in(at_least(1), at_most(1000000)));
  command->add_option("--cases", options->cases_folder, "folder holding berkhoff.toml and harbour.toml")->capture_default_str();
  command->add_option("--scratch", options->scratch,
                      "folder for the generated grids and the baked outputs (default: a new folder in the system's temporary folder)");
  command->add_option("--triad-repeats", m.triad_repeats, "passes of the STREAM triad; the fastest is reported")
      ->capture_default_str()
      ->check(number_in(at_least(1), at_most(1000)));
  command->add_flag("--skip-demo", m.skip_demo, "leave out the demo harbour (its chart and gridding take a while)");
  command->add_flag("--skip-large", m.skip_large, "leave out the 1000 x 900 harbour");
  command->add_flag("--one-thread", m.one_thread_only, "time one thread only (not also every thread)");
  command->add_flag("--skip-seed", m.skip_seed,
                    "leave out the seed configuration's bakes (each case again with solver.equations = weakly_nonlinear "
                    "and adi_passes = 1)");
  command->add_flag("--keep", m.keep_scratch, "keep the scratch folder (the baked sequences) afterwards");
  command->add_flag("--json", options->json, "print the results as JSON");
  command->callback([options]() {
    options->measure.cases_folder = options->cases_folder;
    options->measure.scratch_folder = options->scratch;
    const bench::BakeBenchResult result = bench::run_bake_bench(options->measure);
    if (options->json)
      fmt::print("{}\n", bench::bake_bench_json(result).dump(2));
    else
      fmt::print("{}", bench::bake_bench_text(result));
  });
}

}  // namespace nearshore::tools
