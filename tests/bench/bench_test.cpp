// The bench room's run functions on tiny workloads: the result structs hold the figures of what was
// asked (grid sizes, thread counts, frames), every rate is positive and finite, and the text and
// JSON renderings carry them. The numbers themselves are machine-dependent and not asserted.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "nearshore/bench/bake_bench.hpp"
#include "nearshore/bench/bathy_bench.hpp"
#include "nearshore/bench/deepwater_bench.hpp"
#include "nearshore/bench/loops_bench.hpp"
#include "nearshore/bench/ships_bench.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/core/progress.hpp"

namespace nearshore::bench {
namespace {

namespace fs = std::filesystem;

bool positive_finite(double value) { return std::isfinite(value) && value > 0.0; }

fs::path bench_scratch(const std::string& name) {
  return fs::temp_directory_path() / ("nearshore_bench_test_" + name + "_" + std::to_string(::getpid()));
}

// Two steps of data/cases/berkhoff.toml (600 x 400 cells) at one thread, in the case's own
// configuration (the defaults) and the seed's: both rows carry positive rates and bytes per cell,
// the seed's solver holds fewer bytes per cell (no fully nonlinear remainder, no second pass's
// arrays) and streams fewer per step, and the sequence the seed bake wrote records the equations
// it ran (the case reader's record made again from the changed parameters).
TEST(BenchRoom, BakeOfTheBerkhoffCaseWithItsDefaultsAndInTheSeedConfiguration) {
  ProgressBar::set_quiet(true);
  BakeBenchOptions options;
  options.steps = 2;
  options.triad_repeats = 1;
  options.skip_demo = options.skip_large = options.one_thread_only = true;
  options.cases_folder = fs::path(NEARSHORE_SOURCE_DIR) / "data" / "cases";
  options.scratch_folder = bench_scratch("bake");
  options.keep_scratch = true;  // to read the seed bake's manifest (the last bake into scratch/bake)
  const BakeBenchResult result = run_bake_bench(options);
  ASSERT_EQ(result.bakes.size(), 2u);
  const BakeMeasurement& own = result.bakes[0];
  const BakeMeasurement& seed = result.bakes[1];
  EXPECT_EQ(own.configuration, BakeConfiguration::kCase);
  EXPECT_EQ(own.configuration_name, "defaults");
  EXPECT_EQ(own.solver_record.value("equations", ""), "fully_nonlinear");
  EXPECT_EQ(own.solver_record["adi_passes"], 2);
  EXPECT_EQ(seed.configuration, BakeConfiguration::kSeed);
  EXPECT_EQ(seed.configuration_name, "seed");
  EXPECT_FALSE(seed.solver_record.contains("equations"));  // the record's way of saying weakly nonlinear
  EXPECT_EQ(seed.solver_record["adi_passes"], 1);
  for (const BakeMeasurement& m : result.bakes) {
    EXPECT_EQ(m.name, "Berkhoff case");
    EXPECT_EQ(m.threads, 1);
    EXPECT_EQ(m.steps, 2);
    EXPECT_EQ(m.columns, 600);
    EXPECT_EQ(m.rows, 400);
    EXPECT_TRUE(positive_finite(m.updates_per_s_per_core)) << m.configuration_name;
    EXPECT_TRUE(positive_finite(m.updates_per_cpu_s)) << m.configuration_name;
    EXPECT_TRUE(positive_finite(m.bytes_per_cell)) << m.configuration_name;
    EXPECT_TRUE(positive_finite(m.solver_bytes_per_cell)) << m.configuration_name;
  }
  EXPECT_EQ(own.time_step_s, seed.time_step_s);  // the same case: only the two keys differ
  EXPECT_GT(own.solver_bytes_per_cell, seed.solver_bytes_per_cell);
  EXPECT_GT(own.streamed_bytes_per_cell_step, seed.streamed_bytes_per_cell_step);
  EXPECT_TRUE(std::isnan(own.case_to_seed_time_per_update));
  EXPECT_TRUE(positive_finite(seed.case_to_seed_time_per_update));
  EXPECT_TRUE(positive_finite(seed.case_to_seed_cpu_time_per_update));
  EXPECT_DOUBLE_EQ(seed.case_to_seed_time_per_update, seed.updates_per_s_per_core / own.updates_per_s_per_core);

  const fs::path manifest = options.scratch_folder / "bake" / "manifest.json";
  ASSERT_TRUE(fs::exists(manifest)) << manifest;
  const nlohmann::json recorded = nlohmann::json::parse(std::ifstream(manifest));
  EXPECT_EQ(recorded["solver"], seed.solver_record);
  fs::remove_all(options.scratch_folder);

  const nlohmann::json json = bake_bench_json(result);
  ASSERT_EQ(json["bakes"].size(), 2u);
  EXPECT_EQ(json["bakes"][0]["configuration"], "defaults");
  EXPECT_EQ(json["bakes"][0]["equations"], "fully_nonlinear");
  EXPECT_EQ(json["bakes"][1]["configuration"], "seed");
  EXPECT_EQ(json["bakes"][1]["equations"], "weakly_nonlinear");
  EXPECT_EQ(json["bakes"][1]["adi_passes"], 1);
  for (const nlohmann::json& bake : json["bakes"])
    for (const char* field : {"cell_updates_per_s_per_core", "cell_updates_per_cpu_s", "bytes_per_cell", "solver_bytes_per_cell"})
      EXPECT_TRUE(positive_finite(bake.at(field).get<double>())) << field;
  EXPECT_TRUE(json["bakes"][0]["case_to_seed_time_per_update"].is_null());
  EXPECT_TRUE(positive_finite(json["bakes"][1]["case_to_seed_time_per_update"].get<double>()));
  EXPECT_TRUE(positive_finite(json["bakes"][1]["case_to_seed_cpu_time_per_update"].get<double>()));

  const std::string text = bake_bench_text(result);
  EXPECT_NE(text.find("case/seed"), std::string::npos) << text;
  EXPECT_NE(text.find("Berkhoff case     defaults"), std::string::npos) << text;
  EXPECT_NE(text.find("Berkhoff case     seed"), std::string::npos) << text;
}

TEST(BenchRoom, BathyOnATinyGridInterpolatesEveryCell) {
  ProgressBar::set_quiet(true);
  BathyBenchOptions options;
  options.grid_cells = 24;
  options.soundings = 300;
  options.spacing_m = 5.0;
  const BathyBenchResult result = run_bathy_bench(options);
  ASSERT_GE(result.runs.size(), 1u);
  EXPECT_EQ(result.runs.front().threads, 1);
  for (const BathyBenchRun& run : result.runs) {
    EXPECT_EQ(run.soundings, 304u);  // the square's 4 corners added
    EXPECT_EQ(run.cells, 576u);
    EXPECT_EQ(run.cells_interpolated, 576u);  // the corners make the hull cover every cell
    EXPECT_TRUE(positive_finite(run.soundings_per_s));
    EXPECT_TRUE(positive_finite(run.cells_per_s));
  }
  const nlohmann::json json = bathy_bench_json(result);
  ASSERT_EQ(json.size(), result.runs.size());
  EXPECT_EQ(json[0]["cells"].get<std::size_t>(), 576u);
  const std::string text = bathy_bench_text(result);
  // The header as `nearshore bench bathy` has always printed it.
  EXPECT_EQ(text.substr(0, text.find('\n') + 1),
            "threads   soundings  triangulate s      soundings/s       cells  interpolate s        cells/s\n");
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), static_cast<long>(1 + result.runs.size()));
}

TEST(BenchRoom, BathyRefusesAGridOfOneCellNamingTheParameter) {
  BathyBenchOptions options;
  options.grid_cells = 1;
  try {
    (void)run_bathy_bench(options);
    FAIL() << "a 1-cell grid was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("BathyBenchOptions::grid_cells"), std::string::npos) << e.what();
  }
}

TEST(BenchRoom, DistanceMatrixAtOneAndTwoThreadsWithItsTablePrintedAsMeasured) {
  ProgressBar::set_quiet(true);
  LoopsBenchOptions options;
  options.distance_size_cells = 16;
  options.distance_frames = 6;
  options.work_folder = bench_scratch("loops");
  std::string printed;
  const LoopsBenchResult result = run_loops_bench(options, [&](const LoopsBenchResult& so_far) {
    printed += so_far.distance_runs.empty() ? loops_bench_text_header(so_far) : loops_bench_text_last_row(so_far);
  });
  ASSERT_EQ(result.distance_runs.size(), 2u);
  EXPECT_EQ(result.distance_runs[0].threads, 1);
  EXPECT_EQ(result.distance_runs[1].threads, 2);
  for (const auto& run : result.distance_runs) EXPECT_TRUE(positive_finite(run.pair_cells_per_s));
  EXPECT_EQ(printed.rfind("distance matrix (streamed block Gram, eq. 8-10): 6 frames of 16 x 16 cells\n", 0), 0u) << printed;
  EXPECT_NE(printed.find("  1 thread : "), std::string::npos) << printed;
  EXPECT_NE(printed.find("  2 threads: "), std::string::npos) << printed;
  EXPECT_EQ(loops_bench_json(result)["benchmark"], "distance_matrix");
  EXPECT_FALSE(fs::exists(options.work_folder));  // the scratch is removed
}

TEST(BenchRoom, DeepWaterTileSetOfOneSmallCascade) {
  ProgressBar::set_quiet(true);
  DeepWaterBenchOptions options;
  options.grid_sizes = {16};
  options.cascades = 1;
  options.frames = 2;
  options.sample_frames = 1;
  options.loop_period_s = 10.0;
  options.scratch_folder = bench_scratch("deepwater");
  const DeepWaterBenchResult result = run_deep_water_bench(options);
  ASSERT_EQ(result.runs.size(), 1u);
  const DeepWaterBenchRun& run = result.runs.front();
  EXPECT_EQ(run.grid_size, 16);
  EXPECT_EQ(run.cascades, 1);
  EXPECT_EQ(run.tile_lengths_m.size(), 1u);
  EXPECT_TRUE(positive_finite(run.synthesis_ms_per_frame));
  EXPECT_TRUE(positive_finite(run.tile_set_bytes_per_frame));
  EXPECT_DOUBLE_EQ(run.tile_set_bytes_per_minute, run.tile_set_bytes_per_frame * 30.0 * 60.0);
  EXPECT_NE(deep_water_bench_text(result).find("(Beaufort 6, tile set at 30 fps, piz compression"), std::string::npos);
  EXPECT_FALSE(fs::exists(options.scratch_folder));
}

// The runtime side (nearshore_bench_runtime): one ship of few points on a small grid (32 cells: the
// dispersive layer's least, DispersiveWakeOptions).
TEST(BenchRoom, ShipsOnASmallGridWithAFleetOfOne) {
  ShipsBenchOptions options;
  options.hull_points = 16;
  options.grid_cells = 32;
  options.repeats = 1;
  options.fleet_ships = 1;
  const ShipsBenchResult result = run_ships_bench(options);
  EXPECT_GE(result.hull_points, 16);
  EXPECT_TRUE(positive_finite(result.shallow_water_step.median_ms));
  EXPECT_TRUE(positive_finite(result.fleet_frame.median_ms));
  EXPECT_LE(result.shallow_water_step.fastest_ms, result.shallow_water_step.median_ms);
  const nlohmann::json json = ships_bench_json(result);
  EXPECT_EQ(json["grid"], 32);
  EXPECT_EQ(json["fleet_ships"], 1);
  const std::string text = ships_bench_text(result);
  EXPECT_NE(text.find("a fleet of 1 ships"), std::string::npos) << text;
  EXPECT_NE(text.find("load average (/proc/loadavg): "), std::string::npos) << text;
}

}  // namespace
}  // namespace nearshore::bench
