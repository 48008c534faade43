#include "command_support.hpp"

namespace nearshore::tools {

void add_bench_loops(CLI::App& bench) {
  add_unbuilt_command(bench, "loops", "Benchmark the loops stage", "nearshore bench loops", "its issue is open");
}

}  // namespace nearshore::tools
