// `nearshore bake CASE.toml -o DIR`: read the case, run the bake, print a summary. The work is in
// bake/ (bake_case.hpp, bake_run.hpp); this file only parses options and prints.
#include <cstdio>
#include <memory>
#include <string>

#include <fmt/core.h>

#include "command_support.hpp"
#include "nearshore/bake/bake_case.hpp"
#include "nearshore/bake/bake_estimate.hpp"
#include "nearshore/bake/bake_run.hpp"
#include "nearshore/core/progress.hpp"

namespace nearshore::tools {

void add_bake_command(CLI::App& app) {
  struct Options {
    std::string case_file, output_folder;
    bool resume = false, overwrite = false, allow_over_budget = false, json = false;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand("bake", "Run the Boussinesq solver over a harbour and bake the wave sequence");
  // A missing case file is read_bake_case's to name (exit 1, as the docs promise), not CLI11's (105).
  command->add_option("case", options->case_file, "Case file (.toml or .json; schema in docs/commands/bake.md)")
      ->required();
  command->add_option("-o,--output", options->output_folder, "Output folder: frames, manifest, gauges.csv, checkpoint")
      ->required();
  command->add_flag("--resume", options->resume, "Continue a killed bake from DIR/checkpoint.bin (same result as uninterrupted)");
  command->add_flag("--overwrite", options->overwrite,
                    "Replace the complete sequence or the unfinished bake's checkpoint that DIR holds (refused without)");
  command->add_flag("--allow-over-budget", options->allow_over_budget,
                    "Bake even when the memory or disk estimate exceeds what this machine has (refused without)");
  command->add_flag("--json", options->json, "Print a JSON summary on stdout (no progress bar)");
  set_example(*command, "nearshore bake data/cases/synolakis.toml -o out/synolakis");
  // The bake library names BakeOptions fields in its messages (a checkpoint to resume, the folder).
  const FlagTable flags = {{"BakeOptions::resume", "--resume"},
                           {"BakeOptions::output_folder", "-o"},
                           {"BakeOptions::overwrite", "--overwrite"},
                           {"BakeOptions::allow_over_budget", "--allow-over-budget"},
                           {"CaseReadOptions::allow_over_budget", "--allow-over-budget"}};
  command->callback(naming_flags_in_errors(flags, [options]() {
    if (options->json) ProgressBar::set_quiet(true);
    const bake::BakeCase bake_case = bake::read_bake_case(options->case_file, {options->allow_over_budget});
    bake::BakeOptions bake_options;
    bake_options.output_folder = options->output_folder;
    bake_options.resume = options->resume;
    bake_options.overwrite = options->overwrite;
    bake_options.allow_over_budget = options->allow_over_budget;
    // What the bake will need, before it starts (run_bake refuses it when the machine has less).
    if (!options->json)
      std::fprintf(stderr, "%s\n",
                   fmt::format("estimate: {}", bake::estimate_bake_resources(bake_case, options->resume).describe()).c_str());
    if (const std::string band = bake::describe_carried_band(bake_case); !options->json && !band.empty())
      std::fprintf(stderr, "%s\n", band.c_str());
    if (const std::string derived = bake::describe_derived_solver_settings(bake_case); !options->json && !derived.empty())
      std::fprintf(stderr, "%s\n", derived.c_str());
    if (const std::string structures = bake::describe_structure_layers(bake_case.structure_layers); !options->json && !structures.empty())
      std::fprintf(stderr, "%s\n", structures.c_str());
    // Positions on land or outside the chart (issue 14 item 2): on stderr, also under --json.
    for (const std::string& warning : bake_case.warnings) std::fprintf(stderr, "warning: %s\n", warning.c_str());
    const bake::BakeSummary summary = bake::run_bake(bake_case, bake_options);
    if (options->json) {
      nlohmann::json printed = summary.to_json();
      printed["warnings"] = bake_case.warnings;
      if (!bake_case.structure_layers.empty()) printed["structure_layers"] = bake::structure_layers_record(bake_case.structure_layers);
      std::printf("%s\n", printed.dump(2).c_str());
      return;
    }
    std::printf("%s\n", fmt::format("baked {} frames ({} s apart from t = {} s) into {}", summary.frames, summary.frame_interval_s,
                                    summary.first_frame_time_s, summary.output_folder.string())
                            .c_str());
    std::printf("%s\n", fmt::format("{} cells x {} steps of {:.5g} s in {:.1f} s wall time ({:.1f} s writing outputs): {:.3g} cell-updates/s{}",
                                    summary.cells, summary.steps_this_run, summary.time_step_s, summary.wall_time_s,
                                    summary.output_wall_time_s, summary.cell_updates_per_s,
                                    summary.resumed_from_s >= 0 ? fmt::format(" (resumed from t = {} s)", summary.resumed_from_s) : "")
                            .c_str());
    std::printf("gauges: %s   seed: %llu\n", summary.gauges_csv.string().c_str(),
                static_cast<unsigned long long>(summary.seed));
    if (const nlohmann::json& deep = summary.deep_water; deep.is_object()) {
      std::string line =
          fmt::format("deep water: {} cascades of {}^2, Hs {:.2f} m, {:.1f} MiB of coefficients",
                      deep["cascades"].get<int>(), deep["grid_size"].get<int>(),
                      deep["significant_wave_height_m"].get<double>(),
                      deep["coefficients_bytes"].get<double>() / (1 << 20));
      if (deep.contains("variance_fraction")) {
        const nlohmann::json& zone = deep["blending"];
        line += fmt::format(
            "; the wave maker makes {} of its waves, {:.1f} % of its variance (Hs {:.2f} m); "
            "blending zone {:.0f}-{:.0f} m inland of the source line, predicted mismatch {:.3f} at its end: "
            "{} (criterion {}, docs/deep-water.md)",
            deep["wave_maker_components"].get<int>(), 100.0 * deep["variance_fraction"].get<double>(),
            deep["carried_significant_wave_height_m"].get<double>(), zone["start_m"].get<double>(),
            zone["start_m"].get<double>() + zone["width_m"].get<double>(),
            zone["predicted_relative_rms_end"].get<double>(),
            zone["seamless"].get<bool>() ? "seamless" : "NOT seamless",
            zone["seamless_relative_rms"].get<double>());
      }
      std::printf("%s\n", line.c_str());
    }
  }));
}

}  // namespace nearshore::tools
