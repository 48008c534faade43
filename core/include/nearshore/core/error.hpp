#pragma once
// nearshore::Error: the one exception type the libraries throw for bad input or a failed run.
// Every message carries the file (or object), the place and the fix, e.g.
//   "bathy.tif: 312 cells are NaN near (x=1520 m, y=880 m); fill them with --fill nearest"
// The command line prints what() and exits non-zero; nothing else is needed to act on it.
#include <filesystem>
#include <stdexcept>
#include <string>

namespace nearshore {

class Error : public std::runtime_error {
 public:
  /// subject: the file or object at fault; problem: what is wrong and where; fix: what to do.
  Error(const std::string& subject, const std::string& problem, const std::string& fix = {});
  const std::string& subject() const { return subject_; }
  const std::string& problem() const { return problem_; }
  const std::string& fix() const { return fix_; }

 private:
  std::string subject_, problem_, fix_;
};

/// Throws Error(path, "does not exist"...) unless `path` is an existing regular file.
void require_readable_file(const std::filesystem::path& path, const std::string& what_it_should_be);

}  // namespace nearshore
