// Resource estimate of a bake (bake_estimate.hpp).
//
// kBakeBytesPerCell, how it was measured (2026-11-24, Release build, this 2-core machine, after
// issue 15 cut the solver's arrays): the peak resident set (getrusage ru_maxrss, /usr/bin/time -f
// %M) of bake_runner processes baking one flume case (0.1 m cells, 0.5 m deep, frames, a
// checkpoint and a gauge written, sponges at both ends), less that of a tiny one (12 x 1 m), per
// added cell: 228 B at 1000 x 1000 cells and 278 B at 1000 x 100 (the test below). The difference
// is the sweep's per-thread scratch, which grows with the longest grid side rather than with the
// cells (2.3 kB per column per thread: 41 B per cell of the narrow flume on two threads, 5 B on the
// square grid). Counting the arrays gives the same picture: the solver holds 173 B per cell plus
// its sponge lists (docs/solver.md "Memory", BoussinesqSolver::memory_bytes()); the bake adds the
// two cell-centred flux rasters (8 B), the frame being encoded (half-float channel copies and the
// file in memory, ~26 B) and the harbour grid (13 B): 220 B. Before issue 15 the figure was 640 B
// (530-574 B measured).
//
// Since 2026-11-24 (issue 15, scale) the estimate splits the two: kBakeBytesPerCell = 250 B per
// cell and kBakeBytesPerLinePerThread = 3.5 kB per cell of the longest side per thread (the
// sweep's 19 scratch arrays of 16 lanes and the filter's 128-line block; 4 kB since the sweep's four
// wall arrays of 2026-11-28). Measured on 4000 x 4000 with the defaults
// (the Berkhoff basin at 7.5 x 5 mm, 12 steps, three frames, a checkpoint, two threads; docs/solver.md
// "A whole bake", 2026-11-30): peak 4.33e9 B, 266 B per cell above the 73 MB of code and libraries;
// the estimate gives 4.75e9 B (+9.8 %). BakeEstimate.CoversTheMeasuredPeakOfARealBake checks the narrow flume against the
// estimate's growth per added cell (per-line buffers included).
//
// The FFT deep-water layer ([deep_water], issue 5) is not per cell of the harbour grid: its cost is
// kDeepWaterBytesPerLatticeCell = 152 B per lattice cell (grid_size^2 x cascade_count), counted from
// DeepWaterField's arrays (ocean/src/deep_water.cpp: Cascade and prepare_synthesis; the header
// lists them). The bake builds the field (at the case's load and again to write the coefficient
// files) before it allocates the solver and frees it after, so the true peak is the larger of the
// two phases plus what the freed field leaves in the heap; adding the field whole is an upper
// bound by at most its size. Measured 2026-11-24 (Release, /usr/bin/time -v peak RSS, the coarse
// Tacoma case, 571 x 495 cells of 12 m, 6 s of sea, no checkpoints, 3 cascades; load 7.4-8.9):
// without [deep_water] 139.5 MB; with it at N = 128, 256, 512: 141.6, 148.9, 185.7 MB, i.e.
// +2.1, +9.4, +46.2 MB against fields of 7.5, 29.9, 119.5 MB (152 B x N^2 x 3). At N = 512 the
// field's phase is the peak (185.7 MB = the 66 MB before the solver + 119.5 MB); below it the
// solver's phase is, and the freed field leaves about 45 B per lattice cell resident.
#include "nearshore/bake/bake_estimate.hpp"

#include <sys/statvfs.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include <fmt/core.h>
#include <tbb/info.h>

#include "nearshore/core/error.hpp"
#include "nearshore/bake/wave_statistics.hpp"
#include "nearshore/sequence/sequence_format.hpp"

namespace nearshore::bake {
namespace fs = std::filesystem;
namespace {

// The solver arrays a checkpoint holds (boussinesq_state.cpp), and that resuming reads into
// temporary arrays before it swaps them in.
constexpr double kStateArrays = 9;
// Bytes of one gauge value while gauges.csv is written: the double, its vector's growth slack
// and its text ("{:.9g}," up to 16 characters).
constexpr double kGaugeValueMemoryBytes = 8 + 8 + 16;
constexpr double kGaugeValueTextBytes = 16;
// OpenEXR's header (attributes, channel list) of a frame, generously.
constexpr double kFrameHeaderBytes = 1024;

double channel_bytes(sequence::Precision precision) { return precision == sequence::Precision::kHalf ? 2.0 : 4.0; }

}  // namespace

std::string format_bytes(double bytes) {
  if (!std::isfinite(bytes)) return fmt::format("{} B", bytes);
  constexpr const char* units[] = {"B", "KiB", "MiB", "GiB", "TiB"};
  int unit = 0;
  while (bytes >= 1024 && unit < 4) bytes /= 1024, ++unit;
  if (unit == 0) return fmt::format("{:.0f} B", bytes);
  if (bytes >= 1e4) return fmt::format("{:.3g} {}", bytes, units[unit]);
  return fmt::format("{:.1f} {}", bytes, units[unit]);
}

std::string BakeResourceEstimate::describe() const {
  const std::string deep_water =
      deep_water_bytes > 0 ? fmt::format(" + {} deep water", format_bytes(deep_water_bytes)) : std::string();
  std::string text = fmt::format("{} of memory ({} cells x {:.0f} B + {} + {}{}), {} of disk ({:.0f} frames of {}",
                                 format_bytes(memory_bytes), cells, kBakeBytesPerCell, format_bytes(line_bytes),
                                 format_bytes(kBakeFixedBytes), deep_water,
                                 format_bytes(disk_bytes), frames, format_bytes(frame_bytes));
  if (checkpoint_bytes > 0) text += fmt::format(", checkpoints of {}", format_bytes(checkpoint_bytes));
  return text + ")";
}

BakeResourceEstimate estimate_bake_resources(const BakeCase& bake_case, bool resume) {
  BakeResourceEstimate estimate;
  const GridGeometry& geometry = bake_case.harbour.geometry;
  const double cells = static_cast<double>(geometry.columns) * static_cast<double>(geometry.rows);
  estimate.cells = static_cast<long long>(cells);
  const double dt = bake_case.solver.time_step_s;
  const BakeTiming& timing = bake_case.timing;
  // The step plan of run_bake, in double (no rounding to whole steps: an estimate).
  estimate.steps = std::round(timing.duration_s / dt);
  const double first_frame = std::round(timing.spin_up_s / dt);
  const double per_frame = std::max(1.0, std::round(timing.output_interval_s / dt));
  const double per_gauge = timing.gauge_interval_s > 0 ? std::max(1.0, std::round(timing.gauge_interval_s / dt)) : 1.0;
  estimate.frames = estimate.steps >= first_frame ? std::floor((estimate.steps - first_frame) / per_frame) + 1 : 0;
  estimate.gauge_samples = std::floor(estimate.steps / per_gauge) + 1;
  // Per sample: the time, and each gauge's elevation and flux (P, Q): gauges.csv and gauge_fluxes.csv.
  const double gauge_values = estimate.gauge_samples * (1.0 + 3.0 * static_cast<double>(bake_case.gauges.size()));

  const sequence::FrameEncoding& encoding = bake_case.output.frame_encoding;  // [output] frame_precision
  const double frame_bytes_per_cell = channel_bytes(encoding.surface_elevation) + 2 * channel_bytes(encoding.flux) +
                                      channel_bytes(encoding.breaking);
  // Scan-line files: each line has an offset-table entry and a line header (y, size), 8 bytes each.
  estimate.frame_bytes = cells * frame_bytes_per_cell + 16.0 * geometry.rows + kFrameHeaderBytes;
  if (timing.checkpoint_interval_s > 0) {
    double names = 8;
    for (const GaugeSpec& gauge : bake_case.gauges) names += 8 + static_cast<double>(gauge.name.size());
    // bake_run.cpp (magic, fingerprint, physics revision, gauges), boussinesq_state.cpp (header, 9 sized arrays, checksum;
    // counted as doubles, an upper bound: state version 3 stores two of them as float; version 4, the
    // fully nonlinear equations', adds a count and four float arrays of faces).
    estimate.checkpoint_bytes = 16 + 8 + 4 + names + 8 + gauge_values * 8 + 36 + kStateArrays * (8 + cells * 8) + 8;
    if (bake_case.solver.equations == boussinesq::Equations::kFullyNonlinear) estimate.checkpoint_bytes += 4 + 4 * (8 + cells * 4.1);
    // The wave statistics' state (header, then their sums and envelope; wave_statistics.cpp).
    if (bake_case.output.wave_statistics) estimate.checkpoint_bytes += 24 + cells * WaveStatistics::kBytesPerCell;
  }

  // The wave statistics' sums and envelope came after kBakeBytesPerCell was measured: added here,
  // with the four float bands written at the end (wave_statistics_geotiff.cpp).
  const double statistics_bytes_per_cell = bake_case.output.wave_statistics ? WaveStatistics::kBytesPerCell + 5 * 4.0 : 0.0;
  // Buffers per cell of the longest side, one set per worker thread (the solver's sweep and filter).
  const double threads = std::max(1, tbb::info::default_concurrency());
  estimate.line_bytes = std::max(geometry.columns, geometry.rows) * kBakeBytesPerLinePerThread * threads;
  // The deep-water field's arrays (kDeepWaterBytesPerLatticeCell above: an upper bound).
  if (bake_case.deep_water) {
    const double n = bake_case.deep_water->grid_size;
    estimate.deep_water_bytes =
        n * n * static_cast<double>(bake_case.deep_water->tile_lengths_m.size()) * kDeepWaterBytesPerLatticeCell;
  }
  const double equations_bytes_per_cell =
      (bake_case.solver.equations == boussinesq::Equations::kFullyNonlinear ? kFullyNonlinearBytesPerCell : 0.0) +
      (bake_case.solver.adi_passes > 1 ? kAdiPassesBytesPerCell : 0.0);
  estimate.memory_bytes = kBakeFixedBytes + cells * (kBakeBytesPerCell + statistics_bytes_per_cell + equations_bytes_per_cell) +
                          estimate.line_bytes +
                          estimate.deep_water_bytes + gauge_values * kGaugeValueMemoryBytes +
                          (resume ? kStateArrays * cells * 8 : 0.0);
  const double harbour_grid_bytes = cells * 16 + kFrameHeaderBytes;  // depth.exr: 4 float channels, ZIP at most that
  const double gauges_csv_bytes = gauge_values * kGaugeValueTextBytes;
  // While under way, the checkpoint, gauges.csv and gauge_fluxes.csv are rewritten beside their last copies.
  const double statistics_file_bytes = bake_case.output.wave_statistics ? cells * 16 + kFrameHeaderBytes : 0.0;  // 4 float bands, DEFLATE at most that
  estimate.disk_bytes = estimate.frames * estimate.frame_bytes + harbour_grid_bytes + 2 * gauges_csv_bytes +
                        2 * estimate.checkpoint_bytes + statistics_file_bytes;
  return estimate;
}

std::optional<double> available_memory_bytes() {
  std::ifstream meminfo("/proc/meminfo");
  std::string key, unit;
  double value = 0;
  while (meminfo >> key >> value) {
    std::getline(meminfo, unit);
    if (key == "MemAvailable:") return value * 1024;  // the kernel reports kB (KiB)
  }
  return std::nullopt;
}

std::optional<double> free_disk_bytes(const fs::path& folder) {
  std::error_code ec;
  fs::path existing = fs::absolute(folder, ec);
  if (ec) return std::nullopt;
  while (!fs::exists(existing, ec)) {
    if (!existing.has_relative_path()) return std::nullopt;
    existing = existing.parent_path();
  }
  struct statvfs status {};
  if (::statvfs(existing.c_str(), &status) != 0) return std::nullopt;
  return static_cast<double>(status.f_bavail) * static_cast<double>(status.f_frsize);
}

void check_bake_resources(const BakeCase& bake_case, const BakeResourceEstimate& estimate, const fs::path& output_folder,
                          double replaced_bytes) {
  std::vector<std::string> problems;
  if (const auto memory = available_memory_bytes(); memory && estimate.memory_bytes > *memory)
    problems.push_back(fmt::format("needs about {} of memory ({} cells x {:.0f} B per cell + {}) but this machine has {} "
                                   "available (MemAvailable, /proc/meminfo)",
                                   format_bytes(estimate.memory_bytes), estimate.cells, kBakeBytesPerCell,
                                   format_bytes(kBakeFixedBytes + estimate.line_bytes + estimate.deep_water_bytes),
                                   format_bytes(*memory)));
  if (const auto disk = free_disk_bytes(output_folder); disk && estimate.disk_bytes > *disk + replaced_bytes) {
    std::string parts = fmt::format("{:.4g} frames of {}", estimate.frames, format_bytes(estimate.frame_bytes));
    if (estimate.checkpoint_bytes > 0) parts += fmt::format(", checkpoints of {}", format_bytes(estimate.checkpoint_bytes));
    problems.push_back(fmt::format("needs about {} of disk ({}) but {} is free in {}{}", format_bytes(estimate.disk_bytes),
                                   parts, format_bytes(*disk), output_folder.string(),
                                   replaced_bytes > 0 ? fmt::format(" (plus {} of files the bake replaces)", format_bytes(replaced_bytes))
                                                      : std::string()));
  }
  if (problems.empty()) return;
  std::string problem = "the bake " + problems.front();
  for (std::size_t i = 1; i < problems.size(); ++i) problem += ", and " + problems[i];
  throw Error(bake_case.case_file.string(), problem + "; nothing was written and the solver was not allocated",
              "use a coarser grid or a smaller domain, a shorter time.duration_s or a longer time.output_interval_s, "
              "free memory or disk space or write into another folder; or set BakeOptions::allow_over_budget to bake "
              "anyway (the estimate is an upper bound)");
}

double streamed_bytes_per_cell_step(const BakeCase& bake_case) {
  return boussinesq::streamed_bytes_per_cell_step(bake_case.solver, false);
}

}  // namespace nearshore::bake
