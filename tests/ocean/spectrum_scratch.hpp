#pragma once
// Shared by the spectrum-file tests (spectrum_files_test.cpp, spectrum_netcdf_test.cpp): a per-test
// folder under the system's temporary directory, removed when the test program ends.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

#include <fmt/format.h>

namespace nearshore::ocean::testing {

inline std::filesystem::path spectrum_scratch_directory() {
  struct Removed {
    std::vector<std::filesystem::path> directories;
    ~Removed() {
      std::error_code ignored;
      for (const auto& d : directories) std::filesystem::remove_all(d, ignored);
    }
  };
  static Removed removed;
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / fmt::format("nearshore_spectrum_files_{}_{}_{}", info->test_suite_name(),
                                                           info->name(), static_cast<long>(::getpid()));
  std::filesystem::create_directories(dir);
  if (std::find(removed.directories.begin(), removed.directories.end(), dir) == removed.directories.end())
    removed.directories.push_back(dir);
  return dir;
}

}  // namespace nearshore::ocean::testing
