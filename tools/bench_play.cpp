// `nearshore bench play [SEQ]`: the flags of the runtime's cost benchmark (bench/play_bench.hpp;
// docs/commands/bench.md, issue 12). Without SEQ it first writes a synthetic sequence to --work
// (bench/play_bench_sequence.hpp, the bake side) and measures that.
#include <cstdio>
#include <memory>

#include "command_support.hpp"
#include "nearshore/bench/play_bench.hpp"
#include "nearshore/bench/play_bench_sequence.hpp"
#include "nearshore/core/progress.hpp"

namespace nearshore::tools {

void add_bench_play(CLI::App& bench) {
  struct Options {
    bench::PlayBenchOptions measure;
    bench::PlayBenchSequenceOptions synthetic;
    bool json = false;
  };
  auto o = std::make_shared<Options>();
  bench::PlayBenchOptions& m = o->measure;
  CLI::App* command = bench.add_subcommand("play", "Runtime cost: main-thread CPU per frame, decode, uploads, CPU queries, grids, GPU ms per pass");
  command->add_option("sequence", m.sequence, "Baked sequence (default: a synthetic --size x --size one in --work)");
  command->add_option("--size", o->synthetic.size_cells, "Grid side of the synthetic sequence (cells)")->capture_default_str()
      ->check(number_in(at_least(16), at_most(8192)));
  command->add_option("--frames", o->synthetic.frames, "Frames of the synthetic sequence")->capture_default_str()
      ->check(number_in(at_least(4), at_most(100000)));
  command->add_option("--seconds", m.seconds, "Paced streaming run, seconds of display time")->capture_default_str()
      ->check(number_in(at_least(1), at_most(36000)));
  command->add_option("--queries", m.queries, "CPU queries per measurement")->capture_default_str()
      ->check(number_in(at_least(65536), at_most(1e10)));
  command->add_option("--screen-error", m.screen_error_px, "Screen-space error every grid is set to (pixels)")
      ->capture_default_str()->check(number_in(at_least(0.5), at_most(64)));
  command->add_option("--msaa", m.msaa_samples, "Anti-aliasing samples per pixel of the frame-rate sections (the pass "
                                                "section also runs at 1)")
      ->capture_default_str()->check(number_in(at_least(1), at_most(32)));
  command->add_option("--refraction", m.refraction,
                      "Screen-space refraction of what lies under the water (true/false): its cost is the difference")
      ->capture_default_str();
  command->add_option("--draws", m.draws, "Frames drawn per frame-rate measurement (after one to warm up)")
      ->capture_default_str()->check(number_in(at_least(2), at_most(1000)));
  command->add_option("--work", o->synthetic.work_folder, "Scratch folder for the synthetic sequence (kept for the next run)")
      ->capture_default_str();
  command->add_flag("--json", o->json, "Print the figures as JSON");
  set_example(*command, "xvfb-run -a nearshore bench play --seconds 20");
  command->callback([o] {
    ProgressBar::set_quiet(true);
    bench::PlayBenchOptions measure = o->measure;
    if (measure.sequence.empty()) measure.sequence = bench::play_bench_sequence(o->synthetic);
    const bench::PlayBenchResult result = bench::run_play_bench(measure);
    if (o->json)
      std::printf("%s\n", bench::play_bench_json(result).dump(1).c_str());
    else
      std::fputs(bench::play_bench_text(result).c_str(), stdout);
  });
}

}  // namespace nearshore::tools
