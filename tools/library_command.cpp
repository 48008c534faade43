// `nearshore library LIBRARY.toml -o DIR`: a harbour's sea-state library (docs/commands/library.md).
// Thin: parse options, run the library alone or, started by mpirun/srun, on every rank
// (library/library_run.hpp, library/mpi/library_mpi.hpp), print the summary.
#include <cstdio>
#include <memory>
#include <set>
#include <vector>
#include <string>

#include <fmt/core.h>

#include "command_support.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/core/progress.hpp"
#include "nearshore/library/library_run.hpp"
#include "nearshore/library/operability.hpp"
#include "nearshore/sequence/library_index.hpp"
#ifdef NEARSHORE_HAVE_MPI
#include "nearshore/library/library_mpi.hpp"
#endif

namespace nearshore::tools {
namespace {

int this_rank() {
#ifdef NEARSHORE_HAVE_MPI
  return library::library_mpi_rank();
#else
  return 0;
#endif
}

library::LibrarySummary run(const std::string& library_file, const library::LibraryOptions& options) {
#ifdef NEARSHORE_HAVE_MPI
  if (library::started_by_mpi_launcher()) return library::run_library_mpi(library_file, options);
#endif
  return library::run_library(library_file, options);
}

void print_summary(const library::LibrarySummary& summary) {
  std::string actions;
  for (const auto& [action, count] : summary.actions) actions += fmt::format("{}{} {}", actions.empty() ? "" : ", ", count, action);
  std::printf("%s\n", fmt::format("library {}: {} states, {} baked ({}), {} failed, {} pending", summary.index_file.string(),
                                  summary.states, summary.baked, actions.empty() ? "nothing to do" : actions, summary.failed,
                                  summary.pending)
                          .c_str());
  std::printf("%s\n", fmt::format("{} rank{}, {} wall time, {:.1f} states baked per hour", summary.ranks,
                                  summary.ranks == 1 ? "" : "s", format_duration(summary.wall_time_s), summary.states_per_hour)
                          .c_str());
}

// `nearshore library operability LIB ...`: each berth's downtime over an occurrence table
// (library/operability.hpp, docs/port-study.md). Returns the subcommand, so the parent can tell it ran.
CLI::App* add_operability_command(CLI::App& library_command) {
  struct Options {
    std::string library_folder, occurrence, berths, output, hold;
    double limit_m = 0.0;
    bool json = false;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = library_command.add_subcommand(
      "operability", "Percentage of time each berth's Hs exceeds a limit, over a baked library and an occurrence table of "
                     "offshore conditions (downtime)");
  command->add_option("library", options->library_folder, "The library folder written by `nearshore library -o DIR`")->required();
  command->add_option("--occurrence", options->occurrence,
                      "CSV hs_m,tp_s,direction_deg,probability (direction travelled toward, counter-clockwise from east) "
                      "or hs_m,tp_s,direction_from_deg,probability (nautical: from, clockwise from north)")
      ->required();
  command->add_option("--berths", options->berths,
                      "CSV name,x_m,y_m (metres from the grid's south-west corner) or name,longitude,latitude, or GeoJSON points")
      ->required();
  command->add_option("--threshold-hs", options->limit_m, "Hs above which a berth is not workable, m (e.g. 0.5 for small craft)")
      ->required()
      ->check(number_in(above(0), at_most(30)));
  command->add_option("-o,--output", options->output,
                      "Folder for operability.csv, operability_conditions.csv and operability.png (none: print only)");
  command->add_option("--hold", options->hold,
                      "The library's other axes, which the table has no column for, e.g. tide_m=0.5 (default: each axis's "
                      "first value)");
  command->add_flag("--json", options->json, "Print the result as JSON on stdout (berths, and every condition's state and Hs)");
  set_example(*command, "nearshore library operability harbour-library --occurrence occurrence.csv --berths berths.csv "
                        "--threshold-hs 0.5 -o operability");
  const FlagTable flags = {{"OperabilityRequest::limit_significant_wave_height_m", "--threshold-hs"}};
  command->callback(naming_flags_in_errors(flags, [options]() {
    library::OperabilityRequest request;
    request.library_folder = options->library_folder;
    request.occurrence_file = options->occurrence;
    request.berths_file = options->berths;
    request.limit_significant_wave_height_m = options->limit_m;
    request.held = sequence::parse_sea_conditions(options->hold, "--hold");
    const library::OperabilityResult result = library::compute_operability(request);
    std::vector<std::filesystem::path> files;
    if (!options->output.empty()) files = library::write_operability(result, options->output);
    if (options->json) {
      std::printf("%s\n", result.to_json().dump(2).c_str());
      return;
    }
    std::printf("%s\n", fmt::format("operability over {} ({} conditions, {} states): time Hs exceeds {:.2f} m", 
                                    result.library_folder.string(), result.conditions.size(),
                                    [&] {
                                      std::set<std::string> used;
                                      for (const auto& c : result.conditions) used.insert(c.state_id);
                                      return used.size();
                                    }(),
                                    result.limit_significant_wave_height_m)
                            .c_str());
    std::printf("  %-20s %10s %10s %12s %12s %10s\n", "berth", "x (m)", "y (m)", "exceeded %", "operable %", "max Hs (m)");
    for (const library::OperabilityBerth& berth : result.berths)
      std::printf("  %-20s %10.1f %10.1f %12.2f %12.2f %10.3f\n", berth.berth.name.c_str(), berth.berth.x_m, berth.berth.y_m,
                  berth.exceedance_percent, 100.0 - berth.exceedance_percent, berth.largest_significant_wave_height_m);
    for (const std::filesystem::path& file : files) std::printf("  %s\n", file.string().c_str());
    for (const std::string& note : result.notes) std::printf("  note: %s\n", note.c_str());
  }));
  return command;
}

}  // namespace

void add_library_command(CLI::App& app) {
  struct Options {
    std::string library_file, output_folder;
    bool overwrite = false, json = false;
    int threads = 0;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand(
      "library", "Bake a harbour's sea-state library: one looping sequence per state of a sweep, and its index "
                 "(serial, or on every rank under mpirun/srun)");
  // Required unless a subcommand (operability) runs: checked in the callback.
  command->add_option("library", options->library_file, "Library file (.toml or .json; schema in docs/library.md)");
  command->add_option("-o,--output", options->output_folder, "Library folder: library.json, cases/, states/");
  CLI::App* operability = add_operability_command(*command);
  command->add_flag("--overwrite", options->overwrite,
                    "Bake again the states whose case changed since they were baked (refused without)");
  command->add_option("--threads", options->threads,
                      "Threads inside each bake (0: the machine's cores divided among its ranks)")
      ->check(number_in(at_least(0), at_most(4096)));
  command->add_flag("--json", options->json, "Print a JSON summary on stdout (no progress lines)");
  set_example(*command, "nearshore library data/libraries/harbour.toml -o harbour-library   "
                        "(or: mpirun -np 4 nearshore library ... ; srun nearshore library ...)");
  const FlagTable flags = {{"LibraryOptions::output_folder", "-o"},
                           {"LibraryOptions::overwrite", "--overwrite"},
                           {"LibraryOptions::threads_per_rank", "--threads"}};
  command->callback(naming_flags_in_errors(flags, [options, operability]() {
    if (operability->parsed()) return;
    if (options->library_file.empty()) throw CLI::RequiredError("library");
    if (options->output_folder.empty()) throw CLI::RequiredError("-o,--output");
    library::LibraryOptions library_options;
    library_options.output_folder = options->output_folder;
    library_options.overwrite = options->overwrite;
    library_options.threads_per_rank = options->threads;
    library_options.progress = !options->json;
    library::LibrarySummary summary;
    try {
      summary = run(options->library_file, library_options);
    } catch (const Error&) {
      if (this_rank() != 0) throw ExitStatus{1};  // rank 0 says it, once
      throw;
    }
    if (this_rank() != 0) return;
    if (options->json)
      std::printf("%s\n", summary.to_json().dump(2).c_str());
    else
      print_summary(summary);
    // A failed state does not stop the others, but the run did not make the whole library.
    if (summary.failed > 0) {
      if (!options->json) {
        for (const sequence::LibraryIndex::State& state : sequence::read_library_index(summary.output_folder).states)
          if (state.status == sequence::LibraryStateStatus::kFailed)
            std::fprintf(stderr, "failed: %s: %s\n", state.id.c_str(), state.error.c_str());
        std::fprintf(stderr, "%d state%s failed (the others are baked); their errors are in %s\n", summary.failed,
                     summary.failed == 1 ? "" : "s", summary.index_file.string().c_str());
      }
      throw ExitStatus{2};
    }
  }));
}

}  // namespace nearshore::tools
