#include "command_support.hpp"

namespace nearshore::tools {

void add_demo_command(CLI::App& app) {
  add_unbuilt_command(app, "demo", "Generate the demo harbour and run chart -> bathymetry -> bake -> loops -> screenshot",
                      "nearshore demo -o demo-out", "issue 2, foundation");
}

}  // namespace nearshore::tools
