#include "command_support.hpp"

namespace nearshore::tools {

void add_bench_bathy(CLI::App& bench) {
  add_unbuilt_command(bench, "bathy", "Benchmark the bathy stage", "nearshore bench bathy", "its issue is open");
}

}  // namespace nearshore::tools
