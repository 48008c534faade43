#pragma once
// What a bake will need before it allocates or writes anything: peak resident memory and disk,
// from the case alone, and the comparison with what the machine has (issue 13: a 20000 x 20000
// grid used to climb past 8 GB before anyone said anything, a larger one ended in std::bad_alloc).
// run_bake() refuses a case whose estimate exceeds the machine unless BakeOptions::allow_over_budget.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "nearshore/bake/bake_case.hpp"

namespace nearshore::bake {

/// Peak resident memory of a bake per grid cell, bytes, measured (bake_estimate.cpp says how):
/// the solver's state, work and static arrays (docs/solver.md "Memory"), the frame being encoded,
/// the harbour grid. 221 B measured on a 4000 x 4000 grid (without the wave statistics, which
/// estimate_bake_resources adds), 228 B on 1000 x 1000, rounded up. Buffers that grow with the
/// longest grid side rather than with the cells are kBakeBytesPerLinePerThread.
inline constexpr double kBakeBytesPerCell = 250.0;
/// What the fully nonlinear equations (solver.equations, the default since issue 19) add per cell,
/// bytes: the history of their explicit remainder, the force and the last value on the x and y
/// faces, the faces' subcritical factors, and the breaking strength in the x sweep's layout by which
/// they fade where waves break, all float (docs/solver.md "Memory"); kBakeBytesPerCell was measured
/// with the seed's.
inline constexpr double kFullyNonlinearBytesPerCell = 28.0;
/// What a second ADI pass (solver.adi_passes > 1, the default two since 2026-11-28) adds per cell,
/// bytes: the previous pass's flux increment and surface, double (docs/solver.md "Memory");
/// kBakeBytesPerCell was measured with one pass.
inline constexpr double kAdiPassesBytesPerCell = 16.0;
/// Per cell of the grid's longest side and per worker thread, bytes: the sweep's scratch (23 arrays
/// of 16 lanes of doubles, 2944 B, four of them the walls' mirror flags since 2026-11-28) and the
/// grid-scale filter's block of 128 lines (1024 B), rounded up. On a narrow grid they weigh 50-70 B
/// per cell (the 1000 x 100 flume on two threads).
inline constexpr double kBakeBytesPerLinePerThread = 4096.0;
/// What a bake allocates whatever its grid: worker threads and their stacks, the case, buffers,
/// bytes (bake_runner peaked 9 MiB above its own start-up on a tiny grid on 2 cores; more cores,
/// more stacks). The code and libraries of the process are not counted: they are resident before
/// the bake starts (the `nearshore` executable alone holds about 65 MiB; since the bake reads
/// local-metres grids through bathymetry/, a bake process loads GDAL too, about 40 MiB at start).
inline constexpr double kBakeFixedBytes = 16.0 * 1024 * 1024;

/// Bytes of an FFT deep-water field (ocean::DeepWaterField) per lattice cell, that is per N^2 x
/// cascade_count: the lattice (amplitude float, phase, frequency, harmonic: 28 B), FFTW's complex
/// input and real output of its 10 channels (80 B), the mixed coefficients and their even and odd
/// halves (16 B), the channels' multipliers on the half spectrum (20 B) and the constructor's
/// variance table (8 B): 152 B. bake_estimate.cpp says how it was measured.
inline constexpr double kDeepWaterBytesPerLatticeCell = 152.0;

struct BakeResourceEstimate {
  long long cells = 0;
  /// Counts in double: a mistyped duration may exceed every integer type.
  double steps = 0;             ///< time steps of the whole bake
  double frames = 0;            ///< frames it writes
  double gauge_samples = 0;     ///< rows of gauges.csv (each also held in memory and in each checkpoint)
  double line_bytes = 0;        ///< the per-line buffers: longest side x kBakeBytesPerLinePerThread x threads
  /// [deep_water]: grid_size^2 x cascade_count x kDeepWaterBytesPerLatticeCell (0 without the layer)
  double deep_water_bytes = 0;
  double frame_bytes = 0;       ///< one frame file (as uncompressed: an upper bound for the compressed encodings)
  double checkpoint_bytes = 0;  ///< one checkpoint.bin (0 without checkpoints)
  double memory_bytes = 0;      ///< memory the bake allocates at its peak (compared with MemAvailable)
  /// The finished folder (frames, harbour grid, gauges.csv) plus, while it runs, the checkpoint and
  /// the temporary copy written beside it. Not counted: the deep-water coefficient files and tile
  /// set of a case with [deep_water] (small next to the frames at bake resolutions).
  double disk_bytes = 0;

  /// One line for people: "976 MiB of memory (4000000 cells x 250 B + 13.7 MiB + 16.0 MiB), 36.5 GiB of disk (1201 frames of 30.5 MiB, ...)".
  std::string describe() const;
};

/// The estimate for `bake_case`; `resume` adds what reading a checkpoint holds for a moment.
BakeResourceEstimate estimate_bake_resources(const BakeCase& bake_case, bool resume = false);

/// Bytes one time step of `bake_case`'s solver moves through main memory per grid cell where no
/// wave breaks: the open-water count of boussinesq::streamed_bytes_per_cell_step (docs/solver.md
/// "Memory traffic") for the case's solver parameters. A model, not a measurement: the traffic side
/// of the roofline line of `nearshore bench bake` (bench/bake_bench.hpp).
double streamed_bytes_per_cell_step(const BakeCase& bake_case);

/// MemAvailable of /proc/meminfo, bytes; nullopt where the system does not say.
std::optional<double> available_memory_bytes();
/// Space an unprivileged writer may use on the file system that holds `folder` (statvfs f_bavail),
/// bytes; a folder that does not exist yet is asked about through its nearest existing parent.
std::optional<double> free_disk_bytes(const std::filesystem::path& folder);

/// Throws nearshore::Error (the case file, both numbers, the fix) when the estimate's memory exceeds
/// available_memory_bytes() or its disk exceeds free_disk_bytes(output_folder) plus
/// `replaced_bytes` (files in the folder the bake replaces, whose space it gets back).
void check_bake_resources(const BakeCase& bake_case, const BakeResourceEstimate& estimate,
                          const std::filesystem::path& output_folder, double replaced_bytes = 0);

/// "512 B", "3.4 MiB", "1.2 GiB", "2.0e+03 TiB": a size as people read it.
std::string format_bytes(double bytes);

}  // namespace nearshore::bake
