// `nearshore bench bathy`: throughput of the gridding stage (issue 3): soundings triangulated per
// second (CGAL Delaunay, spatially sorted insertion) and cells interpolated per second (Sibson
// natural neighbours, rows in parallel with oneTBB) on a 2000 x 2000 grid, at 1 and 2 threads.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <tbb/global_control.h>

#include "command_support.hpp"
#include "nearshore/bathymetry/natural_neighbour.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/core/progress.hpp"

namespace nearshore::tools {
namespace {

// Chart-like soundings: jittered points over the square with a smooth harbour-like relief.
std::vector<bathymetry::ScatteredDepth> synthetic_soundings(std::size_t count, double size_m) {
  std::mt19937 random(2026);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<bathymetry::ScatteredDepth> points;
  points.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    const double x = unit(random) * size_m, y = unit(random) * size_m;
    points.push_back({x, y, 5.0 + 40.0 * y / size_m + 4.0 * std::sin(x / 700.0) * std::cos(y / 900.0)});
  }
  // The square's corners, so the hull covers every cell (as a chart's coverage does).
  for (double x : {0.0, size_m})
    for (double y : {0.0, size_m}) points.push_back({x, y, 5.0 + 40.0 * y / size_m});
  return points;
}

}  // namespace

void add_bench_bathy(CLI::App& bench) {
  struct Options {
    int grid_cells = 2000;
    std::size_t soundings = 200000;
    double spacing_m = 10.0;
    bool json = false;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = bench.add_subcommand("bathy", "Soundings/s triangulated and cells/s interpolated (Sibson) on a square grid");
  command->add_option("--grid", options->grid_cells, "Cells per side of the square grid")
      ->check(number_in(at_least(2), at_most(100000)));
  command->add_option("--soundings", options->soundings, "Scattered soundings to triangulate")
      ->check(number_in(at_least(3), at_most(1e9)));
  command->add_option("--spacing", options->spacing_m, "Cell size in metres")
      ->check(number_in(above(0), at_most(100000)));
  command->add_flag("--json", options->json, "Print the results as JSON");
  set_example(*command, "nearshore bench bathy --grid 2000 --soundings 200000");
  command->callback([options]() {
    if (options->grid_cells < 2 || options->soundings < 3)
      throw Error("nearshore bench bathy", "needs --grid >= 2 and --soundings >= 3", "use the defaults");
    ProgressBar::set_quiet(options->json);
    GridGeometry geometry;
    geometry.columns = geometry.rows = options->grid_cells;
    geometry.spacing_m = options->spacing_m;
    const auto points = synthetic_soundings(options->soundings, geometry.width_m());
    nlohmann::json results = nlohmann::json::array();
    const int max_threads = static_cast<int>(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
    for (int threads : {1, max_threads}) {
      tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
      const auto start = std::chrono::steady_clock::now();
      const bathymetry::NaturalNeighbourSurface surface(points);
      const double triangulate_s = seconds_since(start);
      const auto sample_start = std::chrono::steady_clock::now();
      Raster<float> depth;
      {
        ProgressBar progress(fmt::format("interpolating ({} thread{})", threads, threads > 1 ? "s" : ""), geometry.rows, "rows");
        depth = surface.sample(geometry, nullptr, &progress);
      }
      const double interpolate_s = seconds_since(sample_start);
      std::size_t finite = 0;
      for (float d : depth.values()) finite += std::isfinite(d);
      results.push_back({{"threads", threads}, {"soundings", points.size()}, {"triangulate_s", triangulate_s},
                         {"soundings_per_s", points.size() / triangulate_s}, {"cells", geometry.cell_count()},
                         {"cells_interpolated", finite}, {"interpolate_s", interpolate_s},
                         {"cells_per_s", geometry.cell_count() / interpolate_s}});
      if (threads == max_threads) break;
    }
    if (options->json) {
      std::printf("%s\n", results.dump(2).c_str());
      return;
    }
    std::printf("%s\n", fmt::format("{:>7}  {:>10}  {:>13}  {:>15}  {:>10}  {:>13}  {:>13}", "threads", "soundings",
                                    "triangulate s", "soundings/s", "cells", "interpolate s", "cells/s").c_str());
    for (const auto& r : results)
      std::printf("%s\n", fmt::format("{:>7}  {:>10}  {:>13.2f}  {:>15.0f}  {:>10}  {:>13.2f}  {:>13.0f}", r["threads"].get<int>(),
                                      r["soundings"].get<std::size_t>(), r["triangulate_s"].get<double>(),
                                      r["soundings_per_s"].get<double>(), r["cells"].get<std::size_t>(),
                                      r["interpolate_s"].get<double>(), r["cells_per_s"].get<double>()).c_str());
  });
}

}  // namespace nearshore::tools
