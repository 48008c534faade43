#include "command_support.hpp"

namespace nearshore::tools {

void add_bathy_command(CLI::App& app) {
  add_unbuilt_command(app, "bathy", "Turn chart data into a solver-ready harbour grid", "nearshore bathy ../shared/charts/tacoma_us5wa22m/US5WA22M.000 --spacing 10 -o out/tacoma", "issue 3, bathymetry");
}

}  // namespace nearshore::tools
