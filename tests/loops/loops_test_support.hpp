#pragma once
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "nearshore/core/progress.hpp"
#include "nearshore/core/raster.hpp"

namespace nearshore::loops::testing {

inline GridGeometry small_geometry(int columns = 24, int rows = 16, double spacing_m = 5.0) {
  GridGeometry geometry;
  geometry.columns = columns;
  geometry.rows = rows;
  geometry.spacing_m = spacing_m;
  return geometry;
}

inline std::filesystem::path fresh_folder(const std::string& name) {
  ProgressBar::set_quiet(true);
  // Named after the running test too: ctest runs the tests of one executable in parallel (-j 2),
  // and two tests writing the same sequence folder would race.
  const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::string running = test ? std::string(test->test_suite_name()) + "." + test->name() + "_" : "";
  const std::filesystem::path folder = std::filesystem::current_path() / ("loops_test_" + running + name);
  std::filesystem::remove_all(folder);
  return folder;
}

}  // namespace nearshore::loops::testing
