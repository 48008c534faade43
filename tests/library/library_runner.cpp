// The process the library's fault tests start (library_run_test.cpp), alone or under mpirun: the
// same library calls as `nearshore library` (serial, or MPI when a launcher started it), plus the
// faults its environment names, struck at a state's start on one rank (several separated by ','):
//   NEARSHORE_LIBRARY_FAULT=kill-at-start:RANK:N          SIGKILL itself when RANK starts its N-th state
//   NEARSHORE_LIBRARY_FAULT=pause-at-start:RANK:N:FILE    write FILE.waiting and wait (to be killed)
// Prints the run's summary as JSON on stdout (rank 0). Exit 0, 2 when a state failed, 1 on error.
#include <signal.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "nearshore/core/error.hpp"
#include "nearshore/library/library_run.hpp"
#ifdef NEARSHORE_HAVE_MPI
#include "nearshore/library/library_mpi.hpp"
#endif

namespace {

int current_rank() {
#ifdef NEARSHORE_HAVE_MPI
  return nearshore::library::library_mpi_rank();
#else
  return 0;
#endif
}

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::stringstream stream(text);
  for (std::string part; std::getline(stream, part, separator);) parts.push_back(part);
  return parts;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: library_runner LIBRARY.toml DIR [overwrite]\n");
    return 64;
  }
  nearshore::library::LibraryOptions options;
  options.output_folder = argv[2];
  options.overwrite = argc > 3 && std::string(argv[3]) == "overwrite";
  if (const char* faults = std::getenv("NEARSHORE_LIBRARY_FAULT")) {
    struct Fault {
      std::string kind;
      int rank, nth;
      std::string file;
    };
    std::vector<Fault> list;
    for (const std::string& fault : split(faults, ',')) {
      const std::vector<std::string> parts = split(fault, ':');
      list.push_back({parts.at(0), std::stoi(parts.at(1)), std::stoi(parts.at(2)), parts.size() > 3 ? parts[3] : ""});
    }
    options.on_state = [list, started = 0](const std::string&, bool finished) mutable {
      if (finished) return;
      ++started;  // states this rank has started
      for (const Fault& fault : list) {
        if (current_rank() != fault.rank || started != fault.nth) continue;
        if (fault.kind == "kill-at-start") ::kill(::getpid(), SIGKILL);
        std::ofstream(fault.file + ".waiting") << ::getpid() << "\n";
        while (true) ::pause();
      }
    };
  }
  try {
#ifdef NEARSHORE_HAVE_MPI
    const bool mpi = nearshore::library::started_by_mpi_launcher();
    const nearshore::library::LibrarySummary summary =
        mpi ? nearshore::library::run_library_mpi(argv[1], options) : nearshore::library::run_library(argv[1], options);
#else
    const nearshore::library::LibrarySummary summary = nearshore::library::run_library(argv[1], options);
#endif
    if (current_rank() != 0) return 0;
    std::printf("%s\n", summary.to_json().dump(1).c_str());
    return summary.failed > 0 ? 2 : 0;
  } catch (const nearshore::Error& error) {
    if (current_rank() == 0) std::fprintf(stderr, "error: %s\n", error.what());
    return 1;
  }
}
