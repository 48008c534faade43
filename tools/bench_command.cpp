#include "command_support.hpp"

namespace nearshore::tools {

void add_bench_command(CLI::App& app) {
  add_unbuilt_command(app, "bench", "Measure throughput of each stage and print a table", "nearshore bench bake", "issues 3-6");
}

}  // namespace nearshore::tools
