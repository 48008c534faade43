#include "nearshore/bench/bake_bench.hpp"

#include <malloc.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <fstream>
#include <functional>
#include <memory>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>

#include "nearshore/bake/bake_case.hpp"
#include "nearshore/bake/bake_estimate.hpp"
#include "nearshore/bake/bake_run.hpp"
#include "nearshore/bathymetry/demo_harbour.hpp"
#include "nearshore/bathymetry/harbour_builder.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/core/process_usage.hpp"

namespace nearshore::bench {
namespace {

namespace fs = std::filesystem;

// The 1-minute load average, -1 where /proc/loadavg cannot be read.
double load_average_1min() {
  const auto load = load_average();
  return load ? load->one_minute : -1.0;
}

// ---- Memory bandwidth: the STREAM triad a[i] = b[i] + s c[i] (McCalpin 1995) ----

// Arrays of 3 x 128 MiB, far beyond any cache; the best of `repeats` passes. Static chunks so each
// thread touches (first) and streams the same pages.
TriadBandwidth measure_triad(int threads, int repeats) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
  const std::size_t n = std::size_t{16} << 20;
  std::unique_ptr<double[]> a(new double[n]), b(new double[n]), c(new double[n]);
  const auto chunks = [&](const auto& body) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, n / (4 * static_cast<std::size_t>(threads))),
                      [&](const tbb::blocked_range<std::size_t>& r) { body(r.begin(), r.end()); }, tbb::static_partitioner());
  };
  chunks([&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) a[i] = 0.0, b[i] = 1.0, c[i] = 2.0;
  });
  double best_s = 1e300;
  for (int repeat = 0; repeat < repeats; ++repeat) {
    const auto start = std::chrono::steady_clock::now();
    chunks([&](std::size_t begin, std::size_t end) {
      double* __restrict out = a.get();
      const double* __restrict x = b.get();
      const double* __restrict y = c.get();
      for (std::size_t i = begin; i < end; ++i) out[i] = x[i] + 3.0 * y[i];
    });
    best_s = std::min(best_s, seconds_since(start));
  }
  if (a[n / 2] != 7.0) throw Error("nearshore bench bake", "the STREAM triad computed a wrong value", "report this as a bug");
  return {threads, 24.0 * static_cast<double>(n) / best_s};
}

// ---- The cases ----

// A case as users run it: read from its file (inside the measurement: the harbour grid it holds
// is part of a bake's memory), then cut to `steps` time steps from t = 0 with frames from the
// start (its own output and checkpoint intervals), so a short run writes what a long one writes.
struct BenchCase {
  std::string name;
  std::function<bake::BakeCase()> read;
  int steps = 0;
};

bake::BakeCase shortened(bake::BakeCase bake_case, int steps) {
  bake_case.timing.duration_s = steps * bake_case.solver.time_step_s;
  bake_case.timing.spin_up_s = 0.0;
  return bake_case;
}

// data/cases/harbour.toml on the generated demo harbour (`nearshore demo`'s chart and bathy
// stages, run here once into the scratch folder) at the case's own 8 m.
std::function<bake::BakeCase()> demo_harbour_case(const fs::path& case_file, const fs::path& scratch) {
  const bathymetry::DemoHarbourFiles chart = bathymetry::write_demo_harbour(scratch / "demo-chart");
  bathymetry::BathyRequest request;
  request.inputs = {chart.depth_geotiff, chart.structures_geojson, chart.land_geojson, chart.coastline_geojson};
  request.spacing_m = 8.0;
  bathymetry::write_bathymetry_outputs(scratch / "demo-harbour", bathymetry::build_harbour_grid(request));
  const std::string grid = fs::absolute(scratch / "demo-harbour" / "depth.exr").string();
  return [case_file, grid] {
    nlohmann::json document = bake::read_case_document(case_file);
    document["bathymetry"]["file"] = grid;
    return bake::parse_bake_case(document, case_file);
  };
}

// A 1000 x 900 harbour at 9 m (the size of seed 003's Dalian bay grid): 20 m offshore in the
// south shoaling to a beach in the north, a sinuous bed, a porous breakwater (n = 0.4) with an
// entrance; 40 directional components from the south, sponges on three sides. Written as a harbour
// grid and a case file, and read back through the case reader like any other case.
fs::path large_harbour_case(const fs::path& scratch) {
  GridGeometry geometry;
  geometry.columns = 1000;
  geometry.rows = 900;
  geometry.spacing_m = 9.0;
  HarbourGrid harbour = HarbourGrid::open_water(geometry, 20.0f);
  for (int r = 0; r < geometry.rows; ++r)
    for (int c = 0; c < geometry.columns; ++c) {
      const double x = geometry.cell_centre_x_m(c), y = geometry.cell_centre_y_m(r);
      const double depth = 20.0 - 24.0 * y / geometry.height_m() + 2.0 * std::sin(x / 300.0);
      harbour.still_water_depth_m(c, r) = static_cast<float>(depth);
      harbour.land(c, r) = depth < 0.0;
      if (r >= 600 && r < 604 && (c < 450 || c >= 520)) harbour.porosity(c, r) = 0.4f;
    }
  fs::create_directories(scratch / "large-harbour");
  const fs::path depth_exr = scratch / "large-harbour" / "depth.exr", case_file = scratch / "large_harbour.toml";
  write_harbour_grid(depth_exr, harbour);
  std::ofstream(case_file) << fmt::format(
      "title = \"bench: 1000 x 900 harbour at 9 m\"\n"
      "[bathymetry]\nkind = \"harbour_grid\"\nfile = \"{}\"\n"
      "[time]\nduration_s = 600.0\nspin_up_s = 0.0\noutput_interval_s = 2.0\ncourant_number = 0.5\ncheckpoint_interval_s = 60.0\n"
      "[wave_maker]\nkind = \"irregular\"\nfacing = \"south\"\nsource_line_m = 300.0\nspectrum = \"jonswap\"\n"
      "significant_height_m = 1.5\npeak_period_s = 10.0\nfrequency_count = 10\nmin_frequency_hz = 0.06\nmax_frequency_hz = 0.14\n"
      "direction_count = 4\nspreading_s = 20.0\nseed = 3\nramp_time_s = 30.0\n"
      "[solver]\ndispersion_cutoff_depth_m = 0.5\n"
      "[[sponges]]\nside = \"south\"\nwidth_m = 200.0\n[[sponges]]\nside = \"west\"\nwidth_m = 200.0\n"
      "[[sponges]]\nside = \"east\"\nwidth_m = 200.0\n"
      "[[gauges]]\nname = \"entrance\"\nx_m = 4450.0\ny_m = 5420.0\n",
      fs::absolute(depth_exr).string());
  return case_file;
}

// ---- The configurations ----

// The seed configuration of a case as read (docs/solver.md, "Speed"): the seed papers' weakly
// nonlinear equations and one ADI pass, every other parameter the reader resolved kept (time step,
// filter, breaking, sponges), and the record the sequence keeps made again from the parameters
// that run.
bake::BakeCase seed_configuration(bake::BakeCase bake_case) {
  bake_case.solver.equations = boussinesq::Equations::kWeaklyNonlinear;
  bake_case.solver.adi_passes = 1;
  bake_case.solver_record = bake::solver_record_of(bake_case);
  return bake_case;
}

std::string configuration_name(BakeConfiguration configuration, const boussinesq::SolverParameters& solver) {
  if (configuration == BakeConfiguration::kSeed) return "seed";
  const boussinesq::SolverParameters defaults;
  return solver.equations == defaults.equations && solver.adi_passes == defaults.adi_passes ? "defaults" : "case";
}

// ---- One timed bake ----

BakeMeasurement measure(const BenchCase& bench, BakeConfiguration configuration, int threads, const fs::path& output) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
  BakeMeasurement m;
  // Freed heap goes back to the system first, so the resident set before is what is in use and
  // the bake's peak counts every page it needs (reading its case included).
  malloc_trim(0);
  const bool peak_reset = reset_peak_resident_set();
  const double resident_before = resident_set_bytes();
  bake::BakeCase bake_case = shortened(bench.read(), bench.steps);
  if (configuration == BakeConfiguration::kSeed) bake_case = seed_configuration(std::move(bake_case));
  m.name = bench.name;
  m.configuration = configuration;
  m.configuration_name = configuration_name(configuration, bake_case.solver);
  m.solver_record = bake_case.solver_record;
  m.threads = threads;
  m.columns = bake_case.harbour.geometry.columns;
  m.rows = bake_case.harbour.geometry.rows;
  m.steps = bench.steps;
  m.time_step_s = bake_case.solver.time_step_s;
  const double cells = static_cast<double>(bake_case.harbour.geometry.cell_count());
  bake::BakeOptions options;
  options.output_folder = output;
  options.overwrite = true;
  m.load_before = load_average_1min();
  const double cpu_start = process_cpu_s();
  const auto start = std::chrono::steady_clock::now();
  const bake::BakeSummary summary = bake::run_bake(bake_case, options);
  m.wall_s = seconds_since(start);
  m.cpu_s = process_cpu_s() - cpu_start;
  m.load_after = load_average_1min();
  m.peak_resident_bytes = peak_reset ? peak_resident_set_bytes() : summary.peak_resident_bytes;
  m.bytes_per_cell = peak_reset ? (m.peak_resident_bytes - resident_before) / cells : std::nan("");
  m.solver_bytes_per_cell = summary.solver_memory_bytes / cells;
  m.frames = summary.frames;
  m.output_wall_s = summary.output_wall_time_s;
  const double updates = cells * static_cast<double>(summary.steps_this_run);
  m.updates_per_s_per_core = updates / m.wall_s / threads;
  m.updates_per_cpu_s = updates / m.cpu_s;
  m.simulated_s_per_wall_s = static_cast<double>(summary.steps_this_run) * summary.time_step_s / m.wall_s;
  m.streamed_bytes_per_cell_step = bake::streamed_bytes_per_cell_step(bake_case);
  return m;
}

std::string today_utc() {
  const std::time_t now = std::time(nullptr);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
  return text;
}

}  // namespace

double BakeBenchResult::triad_bytes_per_s(int threads) const {
  for (const TriadBandwidth& b : bandwidth)
    if (b.threads == threads) return b.bytes_per_s;
  return bandwidth.front().bytes_per_s;
}

BakeBenchResult run_bake_bench(const BakeBenchOptions& options) {
  if (options.steps < 1 || options.harbour_steps < 1 || options.triad_repeats < 1)
    throw Error("BakeBenchOptions", fmt::format("steps = {}, harbour_steps = {}, triad_repeats = {}: each must be at least 1",
                                                options.steps, options.harbour_steps, options.triad_repeats),
                "use the defaults (200, 10, 10)");
  const fs::path scratch = options.scratch_folder.empty()
                               ? fs::temp_directory_path() / fmt::format("nearshore-bench-bake-{}", ::getpid())
                               : options.scratch_folder;
  fs::create_directories(scratch);
  BakeBenchResult result;
  result.date = today_utc();
  result.hardware_threads = tbb::info::default_concurrency();
  const int all_threads = result.hardware_threads;

  std::vector<BenchCase> cases;
  const fs::path berkhoff = options.cases_folder / "berkhoff.toml";
  cases.push_back({"Berkhoff case", [berkhoff] { return bake::read_bake_case(berkhoff); }, options.steps});
  if (!options.skip_demo)
    cases.push_back({"demo harbour", demo_harbour_case(options.cases_folder / "harbour.toml", scratch), options.steps});
  if (!options.skip_large) {
    const fs::path large = large_harbour_case(scratch);
    cases.push_back({"harbour 1000x900", [large] { return bake::read_bake_case(large); }, options.harbour_steps});
  }

  result.bandwidth = {measure_triad(1, options.triad_repeats)};
  if (all_threads > 1 && !options.one_thread_only) result.bandwidth.push_back(measure_triad(all_threads, options.triad_repeats));
  std::vector<int> thread_counts = {1};
  if (all_threads > 1 && !options.one_thread_only) thread_counts.push_back(all_threads);
  for (const BenchCase& bench : cases)
    for (const int threads : thread_counts) {
      const BakeMeasurement own = measure(bench, BakeConfiguration::kCase, threads, scratch / "bake");
      result.bakes.push_back(own);
      if (options.skip_seed) continue;
      BakeMeasurement seed = measure(bench, BakeConfiguration::kSeed, threads, scratch / "bake");
      // Time per update is the inverse of the rate: the case's over the seed's is the seed's rate over the case's.
      seed.case_to_seed_time_per_update = seed.updates_per_s_per_core / own.updates_per_s_per_core;
      seed.case_to_seed_cpu_time_per_update = seed.updates_per_cpu_s / own.updates_per_cpu_s;
      result.bakes.push_back(std::move(seed));
    }
  if (!options.keep_scratch) fs::remove_all(scratch);
  return result;
}

nlohmann::json bake_bench_json(const BakeBenchResult& result) {
  nlohmann::json out;
  out["date"] = result.date;
  out["bake_bytes_per_cell_estimate"] = bake::kBakeBytesPerCell;
  for (const TriadBandwidth& b : result.bandwidth)
    out["triad_bytes_per_s"].push_back({{"threads", b.threads}, {"bytes_per_s", b.bytes_per_s}});
  // JSON has no NaN: a ratio not measured (the case's own rows, a run without seed rows) is null.
  const auto measured_or_null = [](double value) { return std::isnan(value) ? nlohmann::json() : nlohmann::json(value); };
  for (const BakeMeasurement& m : result.bakes) {
    const double streamed = m.streamed_bytes_per_s();
    out["bakes"].push_back({{"case", m.name}, {"configuration", m.configuration_name},
                            {"equations", m.solver_record.value("equations", "weakly_nonlinear")},
                            {"adi_passes", m.solver_record.value("adi_passes", 0)}, {"columns", m.columns}, {"rows", m.rows}, {"threads", m.threads},
                            {"steps", m.steps}, {"frames", m.frames}, {"time_step_s", m.time_step_s}, {"wall_s", m.wall_s},
                            {"cpu_s", m.cpu_s}, {"output_wall_s", m.output_wall_s},
                            {"cell_updates_per_s_per_core", m.updates_per_s_per_core},
                            {"cell_updates_per_cpu_s", m.updates_per_cpu_s},
                            {"simulated_s_per_wall_s", m.simulated_s_per_wall_s}, {"load_average_before", m.load_before},
                            {"load_average_after", m.load_after}, {"peak_resident_bytes", m.peak_resident_bytes},
                            {"bytes_per_cell", m.bytes_per_cell}, {"solver_bytes_per_cell", m.solver_bytes_per_cell},
                            {"case_to_seed_time_per_update", measured_or_null(m.case_to_seed_time_per_update)},
                            {"case_to_seed_cpu_time_per_update", measured_or_null(m.case_to_seed_cpu_time_per_update)},
                            {"streamed_bytes_per_cell_step", m.streamed_bytes_per_cell_step},
                            {"streamed_bytes_per_s", streamed},
                            {"fraction_of_triad_bandwidth", streamed / result.triad_bytes_per_s(m.threads)}});
  }
  return out;
}

std::string bake_bench_text(const BakeBenchResult& result) {
  std::string text = fmt::format("nearshore bench bake, {}, {} hardware threads\n", result.date, result.hardware_threads);
  text += fmt::format("{:<17} {:<8} {:>9} {:>3} {:>5} {:>8} {:>7} {:>14} {:>14} {:>9} {:>10} {:>8} {:>6} {:>6} {:>8} {:>10}\n",
                      "case", "config", "grid", "thr", "steps", "dt (s)", "wall(s)", "updates/s/core", "updates/CPU-s",
                      "sim s/s", "load", "peak MiB", "B/cell", "solver", "roofline", "case/seed");
  for (const BakeMeasurement& m : result.bakes) {
    text += fmt::format(
        "{:<17} {:<8} {:>9} {:>3} {:>5} {:>8.4f} {:>7.2f} {:>14.3e} {:>14.3e} {:>9.3f} {:>4.2f}-{:<4.2f} {:>8.0f} {:>6.0f} {:>6.0f} "
        "{:>7.0f}%",
        m.name, m.configuration_name, fmt::format("{}x{}", m.columns, m.rows), m.threads, m.steps, m.time_step_s, m.wall_s,
        m.updates_per_s_per_core, m.updates_per_cpu_s, m.simulated_s_per_wall_s, m.load_before, m.load_after,
        m.peak_resident_bytes / (1024.0 * 1024.0), m.bytes_per_cell, m.solver_bytes_per_cell,
        100.0 * m.streamed_bytes_per_s() / result.triad_bytes_per_s(m.threads));
    if (!std::isnan(m.case_to_seed_time_per_update))
      text += fmt::format(" {:>10}", fmt::format("{:.2f} ({:.2f})", m.case_to_seed_time_per_update, m.case_to_seed_cpu_time_per_update));
    text += '\n';
  }
  for (const TriadBandwidth& b : result.bandwidth)
    text += fmt::format("memory bandwidth (STREAM triad, {} thread{}): {:.2f} GB/s\n", b.threads, b.threads == 1 ? "" : "s",
                        b.bytes_per_s * 1e-9);
  // The traffic model of each configuration (of the first case: the count is per cell, the same for every grid).
  std::vector<std::string> streamed;
  for (const BakeMeasurement& m : result.bakes)
    if (m.name == result.bakes.front().name && m.threads == result.bakes.front().threads)
      streamed.push_back(fmt::format("{:.0f} ({})", m.streamed_bytes_per_cell_step, m.configuration_name));
  if (!streamed.empty())
    text += fmt::format("a step streams about {} bytes per cell (boussinesq::streamed_bytes_per_cell_step, the open-water count)\n",
                        fmt::join(streamed, ", "));
  text += fmt::format(
      "config = the case's own solver settings (\"defaults\": the fully nonlinear equations, 2 ADI passes) or \"seed\":\n"
      "the same case and steps with solver.equations = weakly_nonlinear and adi_passes = 1 (the seed papers' equations);\n"
      "updates/s/core = cells x steps / wall time of the whole bake (case read excluded; frames, gauges, checkpoints\n"
      "included) / threads; updates/CPU-s uses the CPU time of all threads (less sensitive to other processes);\n"
      "sim s/s = simulated seconds per wall second; load = 1-minute load average before-after; peak MiB = the\n"
      "process's peak resident set during the bake; B/cell = (that peak - the resident set before the bake) / cells\n"
      "(the bake's estimate uses {:.0f} + {:.0f} fully nonlinear + {:.0f} second ADI pass); solver = the bytes per cell of the\n"
      "solver's arrays (BoussinesqSolver::memory_bytes(): state, work, coefficients, scratch); roofline = bytes\n"
      "streamed per second by the model / the triad bandwidth; case/seed = time per cell-update of the case's own\n"
      "configuration over the seed's, at the same threads, from wall time (from CPU time).\n",
      bake::kBakeBytesPerCell, bake::kFullyNonlinearBytesPerCell, bake::kAdiPassesBytesPerCell);
  return text;
}

}  // namespace nearshore::bench
