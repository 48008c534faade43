#include "validation_bake.hpp"

#include <cstdio>
#include <cstdlib>

#include "nearshore/bake/bake_case.hpp"
#include "nearshore/core/atomic_file.hpp"
#include "nearshore/core/progress.hpp"

namespace nearshore::validation {
namespace fs = std::filesystem;
using nlohmann::json;

fs::path case_file(const std::string& name) { return fs::path(NEARSHORE_SOURCE_DIR) / "data" / "cases" / (name + ".toml"); }
fs::path output_folder(const std::string& name) {
  return fs::path(NEARSHORE_BINARY_DIR) / "validation" / (name + (kFull ? "" : "-ci"));
}

bake::BakeSummary bake_case(const std::string& name, const std::string& run_name, const std::function<void(json&)>& adjust) {
  ProgressBar::set_quiet(!kFull);
  json document = bake::read_case_document(case_file(name));
  adjust(document);
  // A solver variant for every case at once, to compare it with the defaults on the same road
  // (docs/validation.md, "What to change when a number moves"): a JSON object merged into [solver],
  // e.g. NEARSHORE_VALIDATION_SOLVER='{"equations": "weakly_nonlinear"}'. Unset in CI.
  if (const char* variant = std::getenv("NEARSHORE_VALIDATION_SOLVER"); variant != nullptr && *variant != '\0') {
    document["solver"].merge_patch(json::parse(variant));
    std::printf("%s: solver variant %s\n", run_name.c_str(), variant);
  }
  // Likewise for the regular wave maker's keys (only where the case's wave maker is regular).
  if (const char* variant = std::getenv("NEARSHORE_VALIDATION_REGULAR_WAVE_MAKER"); variant != nullptr && *variant != '\0' &&
      document.contains("wave_maker") && document["wave_maker"].value("kind", "") == "regular") {
    document["wave_maker"].merge_patch(json::parse(variant));
    std::printf("%s: wave maker variant %s\n", run_name.c_str(), variant);
  }
  const bake::BakeCase c = bake::parse_bake_case(document, case_file(name));
  bake::BakeOptions options;
  options.output_folder = output_folder(run_name);
  options.overwrite = true;  // the test owns its folder: a second ctest run bakes it again
  const bake::BakeSummary summary = bake::run_bake(c, options);
  std::printf("%s: %lld cells, %ld steps of %.5f s, %.1f s wall, %.3g cell-updates/s\n", run_name.c_str(), summary.cells,
              summary.total_steps, summary.time_step_s, summary.wall_time_s, summary.cell_updates_per_s);
  return summary;
}

void add_gauge(json& document, const std::string& name, double x_m, double y_m) {
  document["gauges"].push_back({{"name", name}, {"x_m", x_m}, {"y_m", y_m}});
}

void write_results(const std::string& run_name, const json& results) {
  write_text_atomically(output_folder(run_name) / "validation.json", results.dump(2));
}

}  // namespace nearshore::validation
