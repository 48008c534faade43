#include "nearshore/bench/library_bench.hpp"

#include <algorithm>
#include <fstream>
#include <thread>

#include <fmt/format.h>
#include <fmt/printf.h>

#include "nearshore/bathymetry/demo_harbour.hpp"
#include "nearshore/bathymetry/harbour_builder.hpp"
#include "nearshore/core/process_usage.hpp"

namespace nearshore::bench {
namespace {
namespace fs = std::filesystem;

// The bench's base case: a regular swell from the south over the demo harbour (as the library tests,
// tests/library/library_run_test.cpp, with a longer run so that the bakes outweigh the start-up).
std::string bench_case(double duration_s) {
  return fmt::format(R"(title = "bench library: demo harbour, regular swell"
[bathymetry]
kind = "harbour_grid"
file = "harbour/depth.exr"
[time]
duration_s = {}
spin_up_s = 30.0
output_interval_s = 1.0
courant_number = 0.5
[wave_maker]
kind = "regular"
facing = "south"
source_line_m = 120.0
height_m = 0.5
period_s = 16.0
ramp_time_s = 10.0
[[sponges]]
side = "south"
width_m = 100.0
[[sponges]]
side = "east"
width_m = 100.0
[[sponges]]
side = "west"
width_m = 100.0
)",
                     duration_s);
}

}  // namespace

double LibraryBenchResult::efficiency_vs_serial(const LibraryBenchRun& run) const {
  return run.states_per_hour / runs.front().states_per_hour;
}

double LibraryBenchResult::efficiency_per_rank(const LibraryBenchRun& run) const {
  return efficiency_vs_serial(run) / std::max(1, run.ranks);
}

LibraryBenchResult run_library_bench(const LibraryBenchOptions& options, const LibraryBenchLauncher& launch) {
  const fs::path work = fs::absolute(options.work_folder);
  fs::remove_all(work);
  fs::create_directories(work);
  const bathymetry::DemoHarbourFiles chart = bathymetry::write_demo_harbour(work / "chart");
  bathymetry::BathyRequest request;
  request.inputs = {chart.depth_geotiff, chart.structures_geojson, chart.land_geojson, chart.coastline_geojson};
  request.spacing_m = options.spacing_m;
  const bathymetry::BathyResult harbour = bathymetry::build_harbour_grid(request);
  bathymetry::write_bathymetry_outputs(work / "harbour", harbour);
  std::ofstream(work / "base.toml") << bench_case(options.duration_s);
  // 8 states: 2 directions x 2 heights x 2 tides (the tide changes the time step and so the cost).
  std::ofstream(work / "library.toml") << "title = \"bench library\"\nbase_case = \"base.toml\"\n[sweep]\n"
                                          "direction_deg = [80.0, 100.0]\nheight_m = [0.5, 1.0]\ntide_m = [0.0, 1.0]\n";

  LibraryBenchResult result;
  result.grid_columns = harbour.grid.geometry.columns;
  result.grid_rows = harbour.grid.geometry.rows;
  result.spacing_m = options.spacing_m;
  result.duration_s = options.duration_s;
  result.with_mpi = options.with_mpi;
  const auto measure = [&](const std::string& label, int ranks) {
    const nlohmann::json summary = launch(work / "library.toml", work / label, ranks);
    LibraryBenchRun run;
    run.label = label;
    run.ranks = ranks;
    run.states_baked = summary["actions"].value("baked", 0);
    run.wall_time_s = summary["wall_time_s"].get<double>();
    run.states_per_hour = summary["states_per_hour"].get<double>();
    result.runs.push_back(run);
  };
  measure("serial", 0);
  if (options.with_mpi)
    for (int ranks : {1, 2}) measure(fmt::format("mpi{}", ranks), ranks);
  result.load_average = proc_loadavg_line();
  result.cores = std::max(1u, std::thread::hardware_concurrency());
  if (!options.keep_work_folder) fs::remove_all(work);
  return result;
}

nlohmann::json library_bench_json(const LibraryBenchResult& result) {
  nlohmann::json rows = nlohmann::json::array();
  for (const LibraryBenchRun& run : result.runs)
    rows.push_back({{"run", run.label},
                    {"ranks", run.ranks},
                    {"states_baked", run.states_baked},
                    {"wall_time_s", run.wall_time_s},
                    {"states_per_hour", run.states_per_hour},
                    {"efficiency_vs_serial", result.efficiency_vs_serial(run)},
                    {"efficiency_per_rank", result.efficiency_per_rank(run)}});
  return {{"states", result.states},
          {"grid_cells", {result.grid_columns, result.grid_rows}},
          {"spacing_m", result.spacing_m},
          {"duration_s", result.duration_s},
          {"runs", rows},
          {"load_average", result.load_average},
          {"cores", result.cores}};
}

std::string library_bench_text(const LibraryBenchResult& result) {
  std::string text = fmt::sprintf(
      "sea-state library of the demo harbour: %d states (%d x %d cells of %g m, %g s of regular swell each, "
      "with loop tables)\n",
      result.states, result.grid_columns, result.grid_rows, result.spacing_m, result.duration_s);
  text += "| run | ranks | states baked | wall time (s) | states per hour | efficiency vs serial | per rank |\n";
  text += "|---|---|---|---|---|---|---|\n";
  for (const LibraryBenchRun& run : result.runs)
    text += fmt::sprintf("| %s | %s | %d | %.2f | %.0f | %.2f | %.2f |\n", run.label,
                         run.ranks == 0 ? "- (one process)" : std::to_string(run.ranks), run.states_baked,
                         run.wall_time_s, run.states_per_hour, result.efficiency_vs_serial(run),
                         result.efficiency_per_rank(run));
  if (!result.with_mpi) text += "this nearshore was built without MPI: only the serial run was measured\n";
  text += fmt::sprintf("load average at the end of the runs: %s (/proc/loadavg); %u cores\n", result.load_average,
                       result.cores);
  return text;
}

}  // namespace nearshore::bench
