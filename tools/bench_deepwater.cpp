#include "command_support.hpp"

namespace nearshore::tools {

void add_bench_deepwater(CLI::App& bench) {
  add_unbuilt_command(bench, "deepwater", "Benchmark the deepwater stage", "nearshore bench deepwater", "its issue is open");
}

}  // namespace nearshore::tools
