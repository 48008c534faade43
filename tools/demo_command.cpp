// `nearshore demo`: the main job on the generated demo harbour, stage by stage:
//   1 chart     generate the georeferenced demo chart inputs (GeoTIFF + GeoJSON)
//   2 bathy     grid them into a solver-ready harbour grid
//   3 bake      run the Boussinesq solver with a time-periodic wave maker
//   4 loops     build the loop tables and inspect the seams
//   5 play      render a playback screenshot
// Each stage prints where its outputs are and how long it took. A stage whose issue is still open
// stops the demo with the plain "not built yet" message (exit 3) instead of pretending.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <fmt/core.h>

#include "command_support.hpp"
#include "nearshore/bathymetry/demo_harbour.hpp"
#include "nearshore/core/progress.hpp"

namespace nearshore::tools {
namespace fs = std::filesystem;
namespace {

struct DemoOptions {
  fs::path output_folder = "demo-out";
};

struct StageResult {
  std::string name, outputs;
  double seconds = 0;
};

// Runs one stage, timing it; `run` returns a one-line description of where the outputs are.
StageResult run_stage(const std::string& name, const std::function<std::string()>& run) {
  std::fprintf(stderr, "== demo stage: %s\n", name.c_str());
  const auto start = std::chrono::steady_clock::now();
  StageResult result{name, run(), 0};
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("%-6s %10s  %s\n", name.c_str(), format_duration(result.seconds).c_str(), result.outputs.c_str());
  std::fflush(stdout);
  return result;
}

void run_demo(const DemoOptions& options) {
  const fs::path chart_folder = options.output_folder / "chart";
  std::printf("%-6s %10s  %s\n", "stage", "time", "outputs");
  run_stage("chart", [&] {
    const auto files = bathymetry::write_demo_harbour(chart_folder);
    return fmt::format("{} (+ coastline, land, breakwaters .geojson)", files.depth_geotiff.string());
  });
  std::fprintf(stderr,
               "nearshore demo: the next stage (bathymetry gridding, issue 3) is not built yet. "
               "The chart inputs above were written; nothing else was computed.\n");
  throw ExitStatus{3};
}

}  // namespace

void add_demo_command(CLI::App& app) {
  auto options = std::make_shared<DemoOptions>();
  CLI::App* demo = app.add_subcommand(
      "demo", "Generate the demo harbour and run chart -> bathymetry -> bake -> loops -> screenshot");
  demo->add_option("-o,--output", options->output_folder, "Folder for every output of the demo")
      ->capture_default_str();
  set_example(*demo, "nearshore demo -o demo-out");
  demo->callback([options] { run_demo(*options); });
}

}  // namespace nearshore::tools
