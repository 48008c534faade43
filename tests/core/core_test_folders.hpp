#pragma once
// The scratch folders of the core tests: one helper, so the suites (built as one unity batch) share it.
#include <filesystem>
#include <string>

namespace nearshore::core_testing {

/// An empty folder nearshore_core_<name> under the temporary directory (emptied if it exists).
inline std::filesystem::path fresh_core_folder(const std::string& name) {
  std::filesystem::path folder = std::filesystem::temp_directory_path() / ("nearshore_core_" + name);
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  return folder;
}

}  // namespace nearshore::core_testing
