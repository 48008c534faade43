// `nearshore bench loops`: the flags of the loops stage's benchmark (bench/loops_bench.hpp): the
// distance matrix, or with --compression the codec table of docs/formats/sequence.md.
#include <cstdio>

#include "command_support.hpp"
#include "nearshore/bench/loops_bench.hpp"
#include "nearshore/core/progress.hpp"

namespace nearshore::tools {

void add_bench_loops(CLI::App& bench) {
  struct Options {
    bench::LoopsBenchOptions measure;
    bool json = false;
    std::string work = "nearshore-bench-loops";
    std::string sequence;  // --compression on this bake's frames instead of the synthetic sea
  };
  auto options = std::make_shared<Options>();
  bench::LoopsBenchOptions& m = options->measure;
  CLI::App* command = bench.add_subcommand("loops", "Distance-matrix throughput and frame decode speed");
  command->add_flag("--compression", m.compression,
                    "Measure size, error and decode speed of every frame codec (none, zip, piz, b44, dwaa, rle, zips, pxr24) instead");
  command->add_option("--size", m.size_cells, "Grid side for the compression table (cells)")
      ->check(number_in(at_least(8), at_most(16384)));
  command->add_option("--frames", m.frames, "Frames for the compression table")
      ->check(number_in(at_least(1), at_most(100000)));
  command->add_option("--distance-size", m.distance_size_cells, "Grid side for the distance benchmark (cells)")
      ->check(number_in(at_least(8), at_most(16384)));
  command->add_option("--distance-frames", m.distance_frames, "Frames for the distance benchmark")
      ->check(number_in(at_least(2), at_most(100000)));
  command->add_option("--sequence", options->sequence,
                      "With --compression: measure on the frames of this baked sequence folder (spread over the "
                      "bake; bake it with [output] frame_precision = \"float\" for exact error columns)")
      ->check(CLI::ExistingDirectory);
  command->add_option("--work", options->work, "Scratch folder (removed afterwards)");
  command->add_flag("--json", options->json, "Print the results as JSON on stdout instead of the table");
  set_example(*command, "nearshore bench loops --compression --size 1024 --frames 16");
  command->callback([options]() {
    ProgressBar::set_quiet(true);
    options->measure.work_folder = options->work;
    options->measure.sequence = options->sequence;
    // The table is printed as it is measured: its header first, then each row.
    const auto print_row = [json = options->json](const bench::LoopsBenchResult& so_far) {
      if (json) return;
      const bool no_rows = so_far.compression ? so_far.codecs.empty() : so_far.distance_runs.empty();
      std::fputs((no_rows ? bench::loops_bench_text_header(so_far) : bench::loops_bench_text_last_row(so_far)).c_str(), stdout);
      if (!no_rows) std::fflush(stdout);
    };
    const bench::LoopsBenchResult result = bench::run_loops_bench(options->measure, print_row);
    if (options->json) std::printf("%s\n", bench::loops_bench_json(result).dump(2).c_str());
  });
}

}  // namespace nearshore::tools
