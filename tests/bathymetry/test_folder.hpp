#pragma once
// A fresh scratch folder per test under the build tree (removed first, kept afterwards to look at).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

inline std::filesystem::path fresh_test_folder(const std::string& name) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::filesystem::path folder = std::filesystem::path(NEARSHORE_BINARY_DIR) / "test-output" / "bathymetry" /
                                       (std::string(info->test_suite_name()) + "." + info->name() + name);
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  return folder;
}
