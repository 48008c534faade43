#include "nearshore/core/error.hpp"

#include <fstream>

namespace nearshore {
namespace {
std::string compose(const std::string& subject, const std::string& problem, const std::string& fix) {
  std::string message = subject.empty() ? problem : subject + ": " + problem;
  if (!fix.empty()) message += "; " + fix;
  return message;
}
}  // namespace

Error::Error(const std::string& subject, const std::string& problem, const std::string& fix)
    : std::runtime_error(compose(subject, problem, fix)), subject_(subject), problem_(problem), fix_(fix) {}

void require_readable_file(const std::filesystem::path& path, const std::string& what_it_should_be) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec))
    throw Error(path.string(), "does not exist", "give the path of " + what_it_should_be);
  if (!std::filesystem::is_regular_file(path, ec))
    throw Error(path.string(), "is not a regular file", "give the path of " + what_it_should_be);
  std::ifstream probe(path, std::ios::binary);
  if (!probe) throw Error(path.string(), "cannot be opened for reading", "check its permissions");
}

}  // namespace nearshore
