#include "command_support.hpp"

namespace nearshore::tools {

void add_bake_command(CLI::App& app) {
  add_unbuilt_command(app, "bake", "Run the Boussinesq solver over a harbour and bake the wave sequence", "nearshore bake case.toml -o out/bake", "issue 4, Boussinesq solver");
}

}  // namespace nearshore::tools
