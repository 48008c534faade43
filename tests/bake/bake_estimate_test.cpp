// The resource estimate of a bake (bake_estimate.hpp): a grid that cannot fit is refused before
// anything is allocated, with the numbers; the bytes per cell still cover a real bake's peak.
#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <tbb/info.h>

#include "bake_test_support.hpp"
#include "nearshore/bake/bake_estimate.hpp"
#include "nearshore/bake/bake_run.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/core/progress.hpp"

namespace nearshore::bake {
namespace {
namespace fs = std::filesystem;
using testing::scratch_folder;
using testing::small_flume_case;
using testing::write_text;

double resident_bytes() {
  std::ifstream statm("/proc/self/statm");
  double pages = 0, resident = 0;
  statm >> pages >> resident;
  return resident * static_cast<double>(::sysconf(_SC_PAGESIZE));
}

TEST(BakeEstimate, CountsFramesCheckpointsAndCells) {
  const auto folder = scratch_folder();
  const BakeCase c = read_bake_case(write_text(folder / "case.toml", small_flume_case(8.0, 2.0)));
  const BakeResourceEstimate estimate = estimate_bake_resources(c);
  EXPECT_EQ(estimate.cells, 720);
  EXPECT_EQ(estimate.frames, 13);
  EXPECT_NEAR(estimate.steps * c.solver.time_step_s, 8.0, 1e-6);
  // Half-float channels: 8 bytes per cell and a header.
  EXPECT_GT(estimate.frame_bytes, 720 * 8);
  EXPECT_LT(estimate.frame_bytes, 720 * 8 + 2048);
  EXPECT_GT(estimate.checkpoint_bytes, 9 * 720 * 8);
  EXPECT_GT(estimate.disk_bytes, 13 * estimate.frame_bytes + 2 * estimate.checkpoint_bytes);
  // The per-line buffers (one set per worker thread, so the figure depends on the machine) are
  // their own term; the rest is per cell, the fully nonlinear equations' and the second ADI pass's
  // arrays included, and the gauges.
  EXPECT_DOUBLE_EQ(estimate.line_bytes, 120 * kBakeBytesPerLinePerThread * std::max(1, tbb::info::default_concurrency()));
  EXPECT_NEAR(estimate.memory_bytes, kBakeFixedBytes + 720 * (kBakeBytesPerCell + kFullyNonlinearBytesPerCell + kAdiPassesBytesPerCell) + estimate.line_bytes, 1e5);
  EXPECT_GT(estimate_bake_resources(c, true).memory_bytes, estimate.memory_bytes);  // reading a checkpoint
  EXPECT_NE(estimate.describe().find("13 frames of"), std::string::npos) << estimate.describe();
  EXPECT_EQ(format_bytes(512), "512 B");
  EXPECT_EQ(format_bytes(3.5 * 1024 * 1024), "3.5 MiB");
}

// [deep_water] adds its field's arrays, kDeepWaterBytesPerLatticeCell per lattice cell: the same
// flume and irregular maker with a 64 x 64, two-cascade field needs 64^2 x 2 x 152 B = 1.19 MiB more,
// and nothing else changes (the per-cell constant of a case without the layer stays as it was).
TEST(BakeEstimate, ADeepWaterLayerAddsItsLatticesToTheMemory) {
  const auto folder = scratch_folder();
  std::string without = small_flume_case(4.0);
  const std::string regular =
      "kind = \"regular\"\nfacing = \"west\"\nsource_line_m = 3.0\nheight_m = 0.02\nperiod_s = 2.0\n";
  without.replace(without.find(regular), regular.size(),
                  "facing = \"west\"\nsource_line_m = 3.0\nkind = \"irregular\"\nsignificant_height_m = 0.02\n"
                  "peak_period_s = 1.5\nfrequency_count = 16\nseed = 99\nloop_period_s = 32.0\nspreading_s = 10.0\n"
                  "direction_count = 8\nmin_frequency_hz = 0.3\nmax_frequency_hz = 1.2\n");
  const std::string with =
      without + "[deep_water]\ngrid_size = 64\ncascade_count = 2\nshortest_wavelength_m = 0.05\n";
  const BakeCase plain = read_bake_case(write_text(folder / "without.toml", without));
  const BakeCase deep = read_bake_case(write_text(folder / "with.toml", with));
  ASSERT_FALSE(plain.deep_water.has_value());
  ASSERT_TRUE(deep.deep_water.has_value());
  const BakeResourceEstimate plain_estimate = estimate_bake_resources(plain);
  const BakeResourceEstimate deep_estimate = estimate_bake_resources(deep);
  const double field_bytes = 64.0 * 64.0 * 2 * kDeepWaterBytesPerLatticeCell;
  EXPECT_EQ(plain_estimate.deep_water_bytes, 0.0);
  EXPECT_DOUBLE_EQ(deep_estimate.deep_water_bytes, field_bytes);
  EXPECT_DOUBLE_EQ(deep_estimate.memory_bytes - plain_estimate.memory_bytes, field_bytes);
  // The default equations are the fully nonlinear ones: their remainder's arrays are counted per cell.
  ASSERT_EQ(plain.solver.equations, boussinesq::Equations::kFullyNonlinear);
  EXPECT_DOUBLE_EQ(plain_estimate.memory_bytes, kBakeFixedBytes +
                                                    plain_estimate.cells * (kBakeBytesPerCell + kFullyNonlinearBytesPerCell + kAdiPassesBytesPerCell) +
                                                    plain_estimate.line_bytes +
                                                    plain_estimate.gauge_samples * (1.0 + 3.0 * plain.gauges.size()) * 32.0);  // t, eta, P, Q
  EXPECT_NE(deep_estimate.describe().find("1.2 MiB deep water"), std::string::npos) << deep_estimate.describe();
  EXPECT_EQ(plain_estimate.describe().find("deep water"), std::string::npos) << plain_estimate.describe();
}

// A 20000 x 20000 grid (4e8 cells: about 240 GiB) is refused at once, before the solver or the
// folder exist. The case's harbour grid is a small flume whose geometry says 20000 x 20000: the
// check reads only the geometry, and the test stays cheap (the case readers build the full grid).
TEST(BakeEstimate, AHugeGridIsRefusedFastWithTheNumbers) {
  ProgressBar::set_quiet(true);
  const auto folder = scratch_folder();
  BakeCase c = read_bake_case(write_text(folder / "case.toml", small_flume_case(8.0, 2.0)));
  c.harbour.geometry.columns = 20000;
  c.harbour.geometry.rows = 20000;
  const BakeResourceEstimate estimate = estimate_bake_resources(c);
  const auto available = available_memory_bytes();
  ASSERT_TRUE(available.has_value()) << "/proc/meminfo has no MemAvailable";
  if (estimate.memory_bytes <= *available) GTEST_SKIP() << "this machine has " << format_bytes(*available) << " available";
  BakeOptions options;
  options.output_folder = folder / "out";
  const double resident_before = resident_bytes();
  const auto start = std::chrono::steady_clock::now();
  try {
    run_bake(c, options);
    FAIL() << "a bake of 4e8 cells was not refused";
  } catch (const Error& error) {
    const std::string message = error.what();
    const std::string per_cell = "GiB of memory (400000000 cells x " + std::to_string(static_cast<int>(kBakeBytesPerCell)) + " B per cell";
    for (const std::string& fragment : {std::string("case.toml: the bake needs about "), per_cell,
                                        std::string("available (MemAvailable, /proc/meminfo)"), std::string("BakeOptions::allow_over_budget")})
      EXPECT_NE(message.find(fragment), std::string::npos) << fragment << " missing in: " << message;
  }
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 1.0);
  EXPECT_LT(resident_bytes() - resident_before, 64e6);
  EXPECT_FALSE(fs::exists(options.output_folder));
}

// The same refusal reached through the case file: a 20000 x 20000 generated flume is refused by the
// case reader before it builds the grid (it used to build 5 GB of harbour grid first), in a moment.
TEST(BakeEstimate, AHugeGeneratedGridIsRefusedByTheCaseReaderBeforeItIsBuilt) {
  const auto folder = scratch_folder();
  std::string text = small_flume_case(8.0, 2.0);
  const std::string grid = "length_m = 12.0\nwidth_m = 0.6\nspacing_m = 0.1\n";
  text.replace(text.find(grid), grid.size(), "length_m = 20000.0\nwidth_m = 20000.0\nspacing_m = 1.0\n");
  const auto available = available_memory_bytes();
  ASSERT_TRUE(available.has_value());
  if (4e8 * kBakeBytesPerCell <= *available) GTEST_SKIP() << "this machine has " << format_bytes(*available) << " available";
  const double resident_before = resident_bytes();
  const auto start = std::chrono::steady_clock::now();
  try {
    (void)read_bake_case(write_text(folder / "huge.toml", text));
    FAIL() << "a case of 4e8 cells was read";
  } catch (const Error& error) {
    const std::string message = error.what();
    for (const std::string fragment : {"huge.toml", "bathymetry.spacing_m", "400000000 cells", "available",
                                       "CaseReadOptions::allow_over_budget"})
      EXPECT_NE(message.find(fragment), std::string::npos) << fragment << " missing in: " << message;
  }
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 1.0);
  EXPECT_LT(resident_bytes() - resident_before, 64e6);
}

// The peak resident set of real bakes (child processes, getrusage) at two grid sizes: the memory
// each added cell costs must stay within kBakeBytesPerCell (measured 530-574 B), and not fall far
// below it either (then the constant would refuse bakes that fit).
TEST(BakeEstimate, CoversTheMeasuredPeakOfARealBake) {
  const auto folder = scratch_folder();
  const auto flume = [&](const std::string& name, double length_m, double width_m) {
    const std::string l = std::to_string(length_m), w = std::to_string(width_m);
    return write_text(folder / name,
                      "[bathymetry]\nkind = \"profile\"\nlength_m = " + l + "\nwidth_m = " + w +
                          "\nspacing_m = 0.1\nprofile = [[0.0, 0.5], [" + l + ", 0.5]]\n"
                          "[time]\nduration_s = 0.5\nspin_up_s = 0.0\noutput_interval_s = 0.5\ncourant_number = 0.5\n"
                          "checkpoint_interval_s = 0.25\n"
                          "[wave_maker]\nkind = \"regular\"\nfacing = \"west\"\nsource_line_m = 3.0\nheight_m = 0.02\n"
                          "period_s = 2.0\nramp_time_s = 2.0\n"
                          "[[sponges]]\nside = \"west\"\nwidth_m = 2.0\n[[sponges]]\nside = \"east\"\nwidth_m = 2.0\n"
                          "[[gauges]]\nname = \"g1\"\nx_m = 5.0\ny_m = 0.3\n");
  };
  const auto peak_bytes = [&](const fs::path& case_file, const fs::path& output) {
    const pid_t pid = fork();
    if (pid == 0) {
      execl(BAKE_RUNNER_PATH, BAKE_RUNNER_PATH, case_file.c_str(), output.c_str(), static_cast<char*>(nullptr));
      _exit(127);
    }
    int status = 0;
    struct rusage usage {};
    wait4(pid, &status, 0, &usage);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << case_file;
    return static_cast<double>(usage.ru_maxrss) * 1024;
  };
  // The runner's own code and libraries are resident before any bake and are not part of the
  // estimate (bake_estimate.hpp): bake_runner without arguments loads them, prints its usage and exits.
  const auto library_baseline_bytes = [] {
    const pid_t pid = fork();
    if (pid == 0) {
      const int null_fd = ::open("/dev/null", O_WRONLY);
      if (null_fd >= 0) ::dup2(null_fd, STDERR_FILENO);
      execl(BAKE_RUNNER_PATH, BAKE_RUNNER_PATH, static_cast<char*>(nullptr));
      _exit(127);
    }
    int status = 0;
    struct rusage usage {};
    wait4(pid, &status, 0, &usage);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 2) << "bake_runner without arguments should print its usage";
    return static_cast<double>(usage.ru_maxrss) * 1024;
  };
  const fs::path small = flume("small.toml", 12.0, 1.0), large = flume("large.toml", 100.0, 10.0);
  const double small_peak = peak_bytes(small, folder / "small"), large_peak = peak_bytes(large, folder / "large");
  const BakeCase large_case = read_bake_case(large);
  const double added_cells = static_cast<double>(large_case.harbour.geometry.cell_count()) -
                             static_cast<double>(read_bake_case(small).harbour.geometry.cell_count());
  const double bytes_per_cell = (large_peak - small_peak) / added_cells;
  RecordProperty("measured_bytes_per_cell", std::to_string(bytes_per_cell));
  // What the estimate adds per added cell: kBakeBytesPerCell and the per-line buffers of the longer side.
  const double estimated_per_cell =
      (estimate_bake_resources(large_case).memory_bytes - estimate_bake_resources(read_bake_case(small)).memory_bytes) / added_cells;
  EXPECT_LE(bytes_per_cell, estimated_per_cell) << "a bake now needs more memory per cell: measure it again (bake_estimate.cpp)";
  EXPECT_GE(bytes_per_cell, 0.6 * estimated_per_cell) << "a bake now needs less memory per cell: measure it again";
  EXPECT_GE(estimate_bake_resources(large_case).memory_bytes, large_peak - library_baseline_bytes());
}

}  // namespace
}  // namespace nearshore::bake
