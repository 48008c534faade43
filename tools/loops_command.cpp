#include "command_support.hpp"

namespace nearshore::tools {

void add_loops_command(CLI::App& app) {
  add_unbuilt_command(app, "loops", "Build loop-transition tables for a baked sequence and report seam quality", "nearshore loops out/bake --png out/loops", "issue 6, sequences and loops");
}

}  // namespace nearshore::tools
