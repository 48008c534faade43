#include "command_support.hpp"

namespace nearshore::tools {

void add_bench_bake(CLI::App& bench) {
  add_unbuilt_command(bench, "bake", "Benchmark the bake stage", "nearshore bench bake", "its issue is open");
}

}  // namespace nearshore::tools
