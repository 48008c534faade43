#include "nearshore/bench/bathy_bench.hpp"

#include <chrono>
#include <cmath>
#include <random>

#include <fmt/format.h>
#include <tbb/global_control.h>

#include "nearshore/bathymetry/natural_neighbour.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/core/process_usage.hpp"
#include "nearshore/core/progress.hpp"

namespace nearshore::bench {
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

BathyBenchResult run_bathy_bench(const BathyBenchOptions& options) {
  if (options.grid_cells < 2)
    throw Error("BathyBenchOptions::grid_cells", fmt::format("= {}: a grid needs at least 2 cells per side", options.grid_cells),
                "use 2 or more");
  if (options.soundings < 3)
    throw Error("BathyBenchOptions::soundings", fmt::format("= {}: a triangulation needs at least 3", options.soundings),
                "use 3 or more");
  if (!(options.spacing_m > 0.0))
    throw Error("BathyBenchOptions::spacing_m", fmt::format("= {}: a cell size must be positive", options.spacing_m),
                "use a positive size in metres");
  GridGeometry geometry;
  geometry.columns = geometry.rows = options.grid_cells;
  geometry.spacing_m = options.spacing_m;
  const auto points = synthetic_soundings(options.soundings, geometry.width_m());
  BathyBenchResult result;
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
    BathyBenchRun run;
    run.threads = threads;
    run.soundings = points.size();
    run.triangulate_s = triangulate_s;
    run.soundings_per_s = points.size() / triangulate_s;
    run.cells = geometry.cell_count();
    run.cells_interpolated = finite;
    run.interpolate_s = interpolate_s;
    run.cells_per_s = geometry.cell_count() / interpolate_s;
    result.runs.push_back(run);
    if (threads == max_threads) break;
  }
  return result;
}

nlohmann::json bathy_bench_json(const BathyBenchResult& result) {
  nlohmann::json runs = nlohmann::json::array();
  for (const BathyBenchRun& r : result.runs)
    runs.push_back({{"threads", r.threads}, {"soundings", r.soundings}, {"triangulate_s", r.triangulate_s},
                    {"soundings_per_s", r.soundings_per_s}, {"cells", r.cells},
                    {"cells_interpolated", r.cells_interpolated}, {"interpolate_s", r.interpolate_s},
                    {"cells_per_s", r.cells_per_s}});
  return runs;
}

std::string bathy_bench_text(const BathyBenchResult& result) {
  std::string text = fmt::format("{:>7}  {:>10}  {:>13}  {:>15}  {:>10}  {:>13}  {:>13}\n", "threads", "soundings",
                                 "triangulate s", "soundings/s", "cells", "interpolate s", "cells/s");
  for (const BathyBenchRun& r : result.runs)
    text += fmt::format("{:>7}  {:>10}  {:>13.2f}  {:>15.0f}  {:>10}  {:>13.2f}  {:>13.0f}\n", r.threads, r.soundings,
                        r.triangulate_s, r.soundings_per_s, r.cells, r.interpolate_s, r.cells_per_s);
  return text;
}

}  // namespace nearshore::bench
