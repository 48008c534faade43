// `nearshore bench library`: the flags of the sea-state library's scaling benchmark
// (bench/library_bench.hpp), and how its runs are started: each a separate `nearshore library ...
// --json` process of this executable, alone and under mpirun with 1 and 2 ranks.
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include <fmt/core.h>

#include "command_support.hpp"
#include "nearshore/bench/library_bench.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/core/progress.hpp"

namespace nearshore::tools {
namespace {
namespace fs = std::filesystem;

// Runs `command` (stdout captured), returning the JSON summary it prints; throws naming the command.
nlohmann::json run_json(const std::string& command) {
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(::popen(command.c_str(), "r"), ::pclose);
  if (!pipe) throw Error(command, "cannot be started", "check that the shell can run it");
  std::string output;
  std::array<char, 4096> buffer{};
  while (std::fgets(buffer.data(), buffer.size(), pipe.get())) output += buffer.data();
  const int status = ::pclose(pipe.release());
  if (status != 0)
    throw Error(command, fmt::format("failed (status {}): {}", status, output), "run it by hand to see its messages");
  return nlohmann::json::parse(output.substr(output.find('{')));
}

// `nearshore library LIBRARY -o OUT --json` by this executable, under mpirun -np RANKS when ranks > 0.
nlohmann::json launch_library(const fs::path& library, const fs::path& out, int ranks) {
  std::string launcher;
#ifdef NEARSHORE_MPIEXEC
  // As root, Open MPI wants to be told (shared/toolchain.md); --oversubscribe: 2 ranks on 2 cores
  // are not more than the machine has, but Open MPI counts the cores it may bind to.
  const std::string root = ::getuid() == 0 ? "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 " : "";
  if (ranks > 0) launcher = fmt::format("{}{} --oversubscribe -np {} ", root, NEARSHORE_MPIEXEC, ranks);
#else
  if (ranks > 0) throw Error("nearshore bench library", "this nearshore was built without MPI", "build it where MPI is found");
#endif
  const std::string self = fs::read_symlink("/proc/self/exe").string();
  const std::string command_line = fmt::format("{}'{}' library '{}' -o '{}' --json 2>'{}.log'", launcher, self,
                                               library.string(), out.string(), out.string());
  std::fprintf(stderr, "bench library: %s\n", command_line.c_str());
  return run_json(command_line);
}

}  // namespace

void add_bench_library(CLI::App& bench) {
  struct Options {
    bench::LibraryBenchOptions measure;
    std::string work = "nearshore-bench-library";
    bool json = false;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command =
      bench.add_subcommand("library", "Sea states per hour with 1 and 2 MPI ranks against a serial run");
  command->add_option("--work", options->work, "Scratch folder (removed afterwards unless --keep)");
  command->add_option("--spacing", options->measure.spacing_m, "Cell size of the demo harbour's grid, metres")
      ->check(number_in(at_least(4), at_most(50)));
  command->add_option("--duration-s", options->measure.duration_s, "Simulated time of each state's bake, seconds")
      ->check(number_in(at_least(40), at_most(3600)));
  command->add_flag("--keep", options->measure.keep_work_folder, "Keep the scratch folder (the libraries and their logs)");
  command->add_flag("--json", options->json, "Print the results as JSON on stdout instead of the table");
  set_example(*command, "nearshore bench library");
  command->callback([options]() {
    ProgressBar::set_quiet(true);
    options->measure.work_folder = options->work;
#ifdef NEARSHORE_MPIEXEC
    options->measure.with_mpi = true;
#endif
    const bench::LibraryBenchResult result = bench::run_library_bench(options->measure, launch_library);
    if (options->json)
      std::printf("%s\n", bench::library_bench_json(result).dump(2).c_str());
    else
      std::fputs(bench::library_bench_text(result).c_str(), stdout);
  });
}

}  // namespace nearshore::tools
