#include "nearshore/core/output_folder.hpp"

#include <fmt/core.h>

#include "nearshore/core/error.hpp"

namespace nearshore {
namespace fs = std::filesystem;

namespace {
bool holds(const fs::path& folder, const char* name) {
  std::error_code ec;
  return fs::exists(folder / name, ec);
}

// Whether two paths name the same folder (either may be missing, then they are the same only if
// they are spelled the same after normalisation).
bool same_folder(const fs::path& a, const fs::path& b) {
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec)) {
    const bool same = fs::equivalent(a, b, ec);
    if (!ec) return same;
  }
  return fs::weakly_canonical(a, ec).lexically_normal() == fs::weakly_canonical(b, ec).lexically_normal();
}
}  // namespace

OutputKind output_kind_of_folder(const fs::path& folder, std::string* marker) {
  const auto found = [&](OutputKind kind, const char* name) {
    if (marker) *marker = name;
    return kind;
  };
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) return OutputKind::kNone;
  // The library first: its index sits at the top of a folder of sequences.
  if (holds(folder, "library.json")) return found(OutputKind::kLibrary, "library.json");
  if (holds(folder, "manifest.json")) return found(OutputKind::kSequence, "manifest.json");
  if (holds(folder, "checkpoint.bin")) return found(OutputKind::kSequence, "checkpoint.bin");
  // A sequence holds depth.exr too (the grid it was baked on); bathy's summary.json or its
  // coastline level set say the folder is a harbour grid.
  if (holds(folder, "depth.exr") && holds(folder, "summary.json")) return found(OutputKind::kHarbourGrid, "summary.json");
  if (holds(folder, "coastline.vdb")) return found(OutputKind::kHarbourGrid, "coastline.vdb");
  return OutputKind::kNone;
}

std::string describe_output_kind(OutputKind kind) {
  switch (kind) {
    case OutputKind::kSequence: return "a baked sequence (written by nearshore bake)";
    case OutputKind::kHarbourGrid: return "a harbour grid (written by nearshore bathy)";
    case OutputKind::kLibrary: return "a sea-state library (written by nearshore library)";
    case OutputKind::kNone: break;
  }
  return "nothing of nearshore's";
}

void check_output_folder(const fs::path& output_folder, OutputKind own_kind, bool overwrite,
                         const std::vector<InputFolder>& inputs, const std::string& output_parameter,
                         const std::string& overwrite_parameter) {
  // 1. Never into a folder the inputs come from, overwrite or not: the outputs would replace them.
  for (const InputFolder& input : inputs)
    if (!input.folder.empty() && same_folder(output_folder, input.folder))
      throw Error(output_folder.string(),
                  fmt::format("is the folder {} comes from ({}): writing there would replace the inputs this run reads "
                              "with its own outputs",
                              input.what, input.folder.string()),
                  fmt::format("choose another {}", output_parameter));
  // 2. Another command's outputs only when allowed.
  std::string marker;
  const OutputKind kind = output_kind_of_folder(output_folder, &marker);
  if (kind == OutputKind::kNone || kind == own_kind || overwrite) return;
  throw Error(output_folder.string(),
              fmt::format("holds {} ({}): this run's outputs would replace some of its files and leave it inconsistent",
                          describe_output_kind(kind), marker),
              overwrite_parameter.empty()
                  ? fmt::format("choose another {} (an empty or new folder)", output_parameter)
                  : fmt::format("choose another {} (an empty or new folder), or set {} to replace what is there",
                                output_parameter, overwrite_parameter));
}

}  // namespace nearshore
