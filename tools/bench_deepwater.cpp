// `nearshore bench deepwater`: the flags of the FFT deep-water benchmark (bench/deepwater_bench.hpp).
#include <cstdio>

#include "command_support.hpp"
#include "nearshore/bench/deepwater_bench.hpp"
#include "nearshore/core/progress.hpp"

namespace nearshore::tools {

void add_bench_deepwater(CLI::App& bench) {
  struct Options {
    bench::DeepWaterBenchOptions measure;
    std::string scratch = "bench_deepwater_tiles";
    bool json = false;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = bench.add_subcommand(
      "deepwater", "Synthesis time per frame of the FFT deep-water cascades and bytes per minute of a baked tile set");
  bench::DeepWaterBenchOptions& m = options->measure;
  command->add_option("--grid", m.grid_sizes, "Grid sizes N (N x N per cascade) to measure")
      ->delimiter(',')
      ->check(number_in(at_least(8), at_most(4096)));
  command->add_option("--cascades", m.cascades, "Number of cascades")
      ->check(number_in(at_least(1), at_most(16)));
  command->add_option("--frames", m.frames, "Frames timed per grid size (the median is reported)")
      ->check(number_in(at_least(1), at_most(100000)));
  command->add_option("--beaufort", m.beaufort, "Beaufort force of the preset sea (1-12)")
      ->check(number_in(at_least(1), at_most(12)));
  command->add_option("--shortest", m.shortest_wavelength_m, "Shortest wavelength resolved by the last cascade (m)")
      ->check(number_in(above(0), unbounded()));
  command->add_option("--loop", m.loop_period_s, "Loop period T_loop (s)")
      ->check(number_in(above(0), at_most(86400)));
  command->add_option("--fps", m.frame_rate_hz, "Frame rate of the baked tile set (frames per second of loop)")
      ->check(number_in(above(0), at_most(1000)));
  command->add_option("--sample-frames", m.sample_frames, "Tile-set frames written per cascade to measure bytes/frame")
      ->check(number_in(at_least(1), at_most(100000)));
  command->add_option("--compression", m.compression, "Tile-set EXR compression (none, zip, piz, b44, dwaa)")
      ->check(CLI::IsMember({"none", "zip", "piz", "b44", "dwaa"}));
  command->add_option("--scratch", options->scratch, "Folder for the sample tile sets (removed afterwards)");
  command->add_flag("--json", options->json, "Print the results as JSON");
  set_example(*command, "nearshore bench deepwater --grid 256,512 --cascades 4");
  command->callback(naming_flags_in_errors(
      {{"DeepWaterBenchOptions::frames", "--frames"},
       {"DeepWaterBenchOptions::cascades", "--cascades"},
       {"DeepWaterBenchOptions::sample_frames", "--sample-frames"},
       {"DeepWaterBenchOptions::frame_rate_hz", "--fps"},
       {"DeepWaterBenchOptions::beaufort", "--beaufort"}},
      [options]() {
        ProgressBar::set_quiet(options->json);
        options->measure.scratch_folder = options->scratch;
        const bench::DeepWaterBenchResult result = bench::run_deep_water_bench(options->measure);
        if (options->json)
          std::printf("%s\n", bench::deep_water_bench_json(result).dump(2).c_str());
        else
          std::fputs(bench::deep_water_bench_text(result).c_str(), stdout);
      }));
}

}  // namespace nearshore::tools
