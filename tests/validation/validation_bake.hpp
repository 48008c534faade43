#pragma once
// The road every laboratory validation takes (the same as `nearshore bake`): a case file of
// data/cases/ read, adjusted by the test (CI grid, added gauges), run with run_bake into
// <build>/validation/<run>[-ci]/, and its results written beside the bake. Shared by the test files
// of this folder; compiled into both executables, so kFull is per executable.
#include <filesystem>
#include <functional>
#include <string>

#include <nlohmann/json.hpp>

#include "nearshore/bake/bake_run.hpp"

namespace nearshore::validation {

#if NEARSHORE_FULL_RESOLUTION
#define VALIDATION_SUITE(name) name##FullResolution
#else
#define VALIDATION_SUITE(name) name
#endif
inline constexpr bool kFull = NEARSHORE_FULL_RESOLUTION != 0;

std::filesystem::path case_file(const std::string& name);
/// <build>/validation/<run_name> (full resolution) or <run_name>-ci.
std::filesystem::path output_folder(const std::string& name);
/// Reads data/cases/<name>.toml, lets the test adjust the document, and runs it like `nearshore bake`.
bake::BakeSummary bake_case(const std::string& name, const std::string& run_name,
                            const std::function<void(nlohmann::json&)>& adjust);
void add_gauge(nlohmann::json& document, const std::string& name, double x_m, double y_m);
/// validation.json beside the bake.
void write_results(const std::string& run_name, const nlohmann::json& results);

}  // namespace nearshore::validation
