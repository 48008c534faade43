// nearshore: bake the harbour, stream the sea. One executable, one subcommand per stage:
//   bathy (chart -> grid), bake (grid -> sequence), loops (sequence -> loop tables and report),
//   play (sequence -> screen), export (sequence -> NetCDF, GeoTIFF, EXR, VDB files),
//   demo (all of it on the generated demo harbour), bench (throughput).
#include <cstdio>
#include <exception>

#include <CLI/CLI.hpp>

#include "command_support.hpp"
#include "nearshore/core/error.hpp"

int main(int argc, char** argv) {
  CLI::App app{"nearshore: bake the waves of a real harbour offline, play them back forever in real time."};
  app.set_version_flag("--version", std::string("nearshore ") + NEARSHORE_VERSION);
  app.require_subcommand(1);
  app.footer("\nStart with: nearshore demo -o demo-out     (docs/commands/demo.md)");
  nearshore::tools::add_bathy_command(app);
  nearshore::tools::add_bake_command(app);
  nearshore::tools::add_loops_command(app);
  nearshore::tools::add_play_command(app);
  nearshore::tools::add_demo_command(app);
  nearshore::tools::add_library_command(app);
  nearshore::tools::add_export_command(app);
  nearshore::tools::add_bench_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const nearshore::tools::ExitStatus& status) {
    return status.code;
  } catch (const nearshore::Error& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
