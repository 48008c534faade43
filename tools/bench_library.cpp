// `nearshore bench library`: sea states baked per hour by `nearshore library` alone and under
// `mpirun -np 1` and `-np 2`, and the efficiency of each against the serial run (docs/library.md,
// "Scaling"). The workload is a small library of the generated demo harbour (coarse cells, a short
// regular swell), every run a separate `nearshore library ... --json` process into its own folder.
#include <unistd.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <algorithm>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "command_support.hpp"
#include "nearshore/bathymetry/demo_harbour.hpp"
#include "nearshore/bathymetry/harbour_builder.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/core/progress.hpp"

namespace nearshore::tools {
namespace {
namespace fs = std::filesystem;

// The bench's base case: a regular swell from the south over the demo harbour (as the library tests,
// tests/library/library_run_test.cpp, with a longer run so that the bakes outweigh the start-up).
std::string bench_case(double duration_s) {
  return fmt::format(R"(title = "bench library: demo harbour, regular swell"
[bathymetry]
kind = "harbour_grid"
file = "harbour/depth.exr"
[time]
duration_s = {}
spin_up_s = 30.0
output_interval_s = 1.0
courant_number = 0.5
[wave_maker]
kind = "regular"
facing = "south"
source_line_m = 120.0
height_m = 0.5
period_s = 16.0
ramp_time_s = 10.0
[[sponges]]
side = "south"
width_m = 100.0
[[sponges]]
side = "east"
width_m = 100.0
[[sponges]]
side = "west"
width_m = 100.0
)",
                     duration_s);
}

struct Measured {
  std::string label;
  int ranks = 0;
  nlohmann::json summary;
};

// Runs `command` (stdout captured), returning the JSON summary it prints; throws naming the command.
nlohmann::json run_json(const std::string& command) {
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(::popen(command.c_str(), "r"), ::pclose);
  if (!pipe) throw Error(command, "cannot be started", "check that the shell can run it");
  std::string output;
  std::array<char, 4096> buffer{};
  while (std::fgets(buffer.data(), buffer.size(), pipe.get())) output += buffer.data();
  const int status = ::pclose(pipe.release());
  if (status != 0)
    throw Error(command, fmt::format("failed (status {}): {}", status, output), "run it by hand to see its messages");
  return nlohmann::json::parse(output.substr(output.find('{')));
}

}  // namespace

void add_bench_library(CLI::App& bench) {
  struct Options {
    std::string work = "nearshore-bench-library";
    double spacing_m = 12.0, duration_s = 90.0;
    bool keep = false, json = false;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command =
      bench.add_subcommand("library", "Sea states per hour with 1 and 2 MPI ranks against a serial run");
  command->add_option("--work", options->work, "Scratch folder (removed afterwards unless --keep)");
  command->add_option("--spacing", options->spacing_m, "Cell size of the demo harbour's grid, metres")
      ->check(number_in(at_least(4), at_most(50)));
  command->add_option("--duration-s", options->duration_s, "Simulated time of each state's bake, seconds")
      ->check(number_in(at_least(40), at_most(3600)));
  command->add_flag("--keep", options->keep, "Keep the scratch folder (the libraries and their logs)");
  command->add_flag("--json", options->json, "Print the results as JSON on stdout instead of the table");
  set_example(*command, "nearshore bench library");
  command->callback([options]() {
    ProgressBar::set_quiet(true);
    const fs::path work = fs::absolute(options->work);
    fs::remove_all(work);
    fs::create_directories(work);
    const bathymetry::DemoHarbourFiles chart = bathymetry::write_demo_harbour(work / "chart");
    bathymetry::BathyRequest request;
    request.inputs = {chart.depth_geotiff, chart.structures_geojson, chart.land_geojson, chart.coastline_geojson};
    request.spacing_m = options->spacing_m;
    const bathymetry::BathyResult harbour = bathymetry::build_harbour_grid(request);
    bathymetry::write_bathymetry_outputs(work / "harbour", harbour);
    std::ofstream(work / "base.toml") << bench_case(options->duration_s);
    // 8 states: 2 directions x 2 heights x 2 tides (the tide changes the time step and so the cost).
    std::ofstream(work / "library.toml") << "title = \"bench library\"\nbase_case = \"base.toml\"\n[sweep]\n"
                                            "direction_deg = [80.0, 100.0]\nheight_m = [0.5, 1.0]\ntide_m = [0.0, 1.0]\n";

    const std::string self = fs::read_symlink("/proc/self/exe").string();
    const std::string library = (work / "library.toml").string();
    std::vector<Measured> runs;
    const auto measure = [&](const std::string& label, int ranks, const std::string& launcher) {
      const fs::path out = work / label;
      const std::string command_line = fmt::format("{}'{}' library '{}' -o '{}' --json 2>'{}.log'", launcher, self, library,
                                                   out.string(), out.string());
      std::fprintf(stderr, "bench library: %s\n", command_line.c_str());
      runs.push_back({label, ranks, run_json(command_line)});
    };
    measure("serial", 0, "");
#ifdef NEARSHORE_MPIEXEC
    // As root, Open MPI wants to be told (shared/toolchain.md); --oversubscribe: 2 ranks on 2 cores
    // are not more than the machine has, but Open MPI counts the cores it may bind to.
    const std::string root = ::getuid() == 0 ? "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 " : "";
    for (int ranks : {1, 2})
      measure(fmt::format("mpi{}", ranks), ranks, fmt::format("{}{} --oversubscribe -np {} ", root, NEARSHORE_MPIEXEC, ranks));
    const char* mpi_note = "";
#else
    const char* mpi_note = "this nearshore was built without MPI: only the serial run was measured\n";
#endif

    const std::string load = proc_loadavg_line();
    const double serial_rate = runs.front().summary["states_per_hour"].get<double>();
    if (options->json) {
      nlohmann::json rows = nlohmann::json::array();
      for (const Measured& m : runs) {
        const double rate = m.summary["states_per_hour"].get<double>();
        rows.push_back({{"run", m.label},
                        {"ranks", m.ranks},
                        {"states_baked", m.summary["actions"].value("baked", 0)},
                        {"wall_time_s", m.summary["wall_time_s"].get<double>()},
                        {"states_per_hour", rate},
                        {"efficiency_vs_serial", rate / serial_rate},
                        {"efficiency_per_rank", rate / serial_rate / std::max(1, m.ranks)}});
      }
      const nlohmann::json out = {{"states", 8},
                                  {"grid_cells", {harbour.grid.geometry.columns, harbour.grid.geometry.rows}},
                                  {"spacing_m", options->spacing_m},
                                  {"duration_s", options->duration_s},
                                  {"runs", rows},
                                  {"load_average", load},
                                  {"cores", std::max(1u, std::thread::hardware_concurrency())}};
      std::printf("%s\n", out.dump(2).c_str());
    } else {
      std::printf("sea-state library of the demo harbour: 8 states (%d x %d cells of %g m, %g s of regular swell each, "
                  "with loop tables)\n",
                  harbour.grid.geometry.columns, harbour.grid.geometry.rows, options->spacing_m, options->duration_s);
      std::printf("| run | ranks | states baked | wall time (s) | states per hour | efficiency vs serial | per rank |\n");
      std::printf("|---|---|---|---|---|---|---|\n");
      for (const Measured& m : runs) {
        const double rate = m.summary["states_per_hour"].get<double>();
        const int ranks = std::max(1, m.ranks);
        std::printf("| %s | %s | %d | %.2f | %.0f | %.2f | %.2f |\n", m.label.c_str(),
                    m.ranks == 0 ? "- (one process)" : std::to_string(m.ranks).c_str(),
                    m.summary["actions"].value("baked", 0), m.summary["wall_time_s"].get<double>(), rate,
                    rate / serial_rate, rate / serial_rate / ranks);
      }
      std::printf("%sload average at the end of the runs: %s (/proc/loadavg); %u cores\n", mpi_note, load.c_str(),
                  std::max(1u, std::thread::hardware_concurrency()));
    }
    if (!options->keep) fs::remove_all(work);
  });
}

}  // namespace nearshore::tools
