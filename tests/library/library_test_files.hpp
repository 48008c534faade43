#pragma once
// Files the library tests write: one helper, so the suites (built as one unity batch) share it.
#include <filesystem>
#include <fstream>
#include <string>

namespace nearshore::library::testing {

/// Writes `text` to `file` (replacing it) and returns the path, so a call can sit where the path is needed.
inline std::filesystem::path write_text_file(const std::filesystem::path& file, const std::string& text) {
  std::ofstream(file) << text;
  return file;
}

}  // namespace nearshore::library::testing
