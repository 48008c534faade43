#pragma once
// Shared by the bake tests: a scratch folder per test, a small flume case that runs in well under a
// second, written as TOML text so the tests go through the same parser as a user, and the check
// that a bad case fails with one message naming the file, the key and the fix.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "nearshore/bake/bake_case.hpp"
#include "nearshore/bake/bake_gauges.hpp"
#include "nearshore/core/error.hpp"

namespace nearshore::bake::testing {

using namespace nearshore::ocean;
using namespace nearshore::boussinesq;

/// The current test's scratch folder (created if needed, contents kept).
inline std::filesystem::path current_scratch_folder() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::filesystem::path folder =
      std::filesystem::path(NEARSHORE_BINARY_DIR) / "tests" / "bake" / "scratch" / (std::string(info->test_suite_name()) + "." + info->name());
  std::filesystem::create_directories(folder);
  return folder;
}

/// The current test's scratch folder, emptied.
inline std::filesystem::path scratch_folder() {
  std::filesystem::remove_all(current_scratch_folder());
  return current_scratch_folder();
}

inline std::filesystem::path write_text(const std::filesystem::path& file, const std::string& text) {
  std::ofstream(file) << text;
  return file;
}

/// A 12 m x 0.6 m flume, 0.5 m deep, regular 2 s waves from the west, sponges at both ends,
/// two gauges: about 100 x 6 cells and 400 steps.
inline std::string small_flume_case(double duration_s = 8.0, double checkpoint_interval_s = 0.0) {
  return "title = \"small flume\"\n"
         "[bathymetry]\nkind = \"profile\"\nlength_m = 12.0\nwidth_m = 0.6\nspacing_m = 0.1\n"
         "profile = [[0.0, 0.5], [12.0, 0.5]]\n"
         "[time]\nduration_s = " + std::to_string(duration_s) +
         "\nspin_up_s = 2.0\noutput_interval_s = 0.5\ncourant_number = 0.5\n"
         "checkpoint_interval_s = " + std::to_string(checkpoint_interval_s) +
         "\n[wave_maker]\nkind = \"regular\"\nfacing = \"west\"\nsource_line_m = 3.0\nheight_m = 0.02\nperiod_s = 2.0\n"
         "ramp_time_s = 2.0\n"
         "[[sponges]]\nside = \"west\"\nwidth_m = 2.0\n[[sponges]]\nside = \"east\"\nwidth_m = 3.0\n"
         "[[gauges]]\nname = \"g1\"\nx_m = 5.0\ny_m = 0.3\n[[gauges]]\nname = \"g2\"\nx_m = 7.5\ny_m = 0.3\n";
}

/// The case text must fail to read with ONE nearshore::Error whose message names the case file,
/// contains every `expected` fragment, and carries a fix after "; ".
inline void expect_case_error(const std::string& text, const std::vector<std::string>& expected,
                              const std::string& extension = ".toml") {
  const auto file = write_text(current_scratch_folder() / ("case" + extension), text);
  try {
    read_bake_case(file);
    ADD_FAILURE() << "no error for a case expected to fail with: " << expected.front();
  } catch (const Error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find(file.string()), std::string::npos) << message;
    for (const auto& fragment : expected)
      EXPECT_NE(message.find(fragment), std::string::npos) << "missing '" << fragment << "' in: " << message;
    EXPECT_NE(message.find("; "), std::string::npos) << "no fix in: " << message;
  }
}

/// 4 standard deviations of a gauge's eta over from_s < t <= to_s (Hs; for a regular wave,
/// 2 sqrt(2) sigma is its height H, i.e. half this times sqrt(2)). Fails the test if the window holds
/// fewer than 20 samples.
inline double gauge_four_sigma_m(const GaugeTable& table, const std::string& name, double from_s, double to_s) {
  const std::vector<double>& eta = gauge_column(table, name);
  double sum = 0.0, sum2 = 0.0;
  int n = 0;
  for (std::size_t i = 0; i < eta.size(); ++i)
    if (table.time_s[i] > from_s && table.time_s[i] <= to_s) sum += eta[i], sum2 += eta[i] * eta[i], ++n;
  EXPECT_GT(n, 20) << "gauge " << name << ": too few samples in " << from_s << " .. " << to_s << " s";
  if (n == 0) return 0.0;
  const double mean = sum / n;
  return 4.0 * std::sqrt(std::max(sum2 / n - mean * mean, 0.0));
}

}  // namespace nearshore::bake::testing
