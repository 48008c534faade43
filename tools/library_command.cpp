// `nearshore library LIBRARY.toml -o DIR`: a harbour's sea-state library (docs/commands/library.md).
// Thin: parse options, run the library alone or, started by mpirun/srun, on every rank
// (library/library_run.hpp, library/mpi/library_mpi.hpp), print the summary.
#include <cstdio>
#include <memory>
#include <string>

#include <fmt/core.h>

#include "command_support.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/core/progress.hpp"
#include "nearshore/library/library_run.hpp"
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
  command->add_option("library", options->library_file, "Library file (.toml or .json; schema in docs/library.md)")->required();
  command->add_option("-o,--output", options->output_folder, "Library folder: library.json, cases/, states/")->required();
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
  command->callback(naming_flags_in_errors(flags, [options]() {
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
