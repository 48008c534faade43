// `nearshore demo`: the main job on the generated demo harbour, stage by stage:
//   1 chart     generate the georeferenced demo chart inputs (GeoTIFF + GeoJSON)
//   2 bathy     grid them into a solver-ready harbour grid (nearshore bathy)
//   3 bake      bake a time-periodic swell over it (nearshore bake, case data/cases/harbour.toml)
//   4 loops     build the loop tables and inspect the seams (nearshore loops)
//   5 play      render a playback screenshot (nearshore play)
// Each stage prints where its outputs are and how long it took; the same library calls as the
// individual commands, so the demo exercises exactly what users run.
#include <fmt/core.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "command_support.hpp"
#include "nearshore/bake/bake_case.hpp"
#include "nearshore/bake/bake_run.hpp"
#include "nearshore/bathymetry/demo_harbour.hpp"
#include "nearshore/bathymetry/harbour_builder.hpp"
#include "nearshore/core/atomic_file.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/core/process_usage.hpp"
#include "nearshore/core/progress.hpp"
#include "nearshore/loops/inspector.hpp"
#include "nearshore/plot/plot.hpp"

namespace nearshore::tools {

/// data/cases/harbour.toml, embedded at build time (tools/CMakeLists.txt), so the demo bakes exactly
/// the documented example case.
extern const char* const kDemoHarbourCase;
extern const char* const kDemoIrregularCase;

namespace fs = std::filesystem;
namespace {

struct DemoOptions {
  fs::path output_folder = "demo-out";
  double spacing_m = 8.0;
};

// Runs one stage, timing it; `run` returns a one-line description of where the outputs are.
void run_stage(const std::string& name, const std::function<std::string()>& run) {
  std::fprintf(stderr, "== demo stage: %s\n", name.c_str());
  const auto start = std::chrono::steady_clock::now();
  const std::string outputs = run();
  const double seconds = seconds_since(start);
  std::printf("%-9s %10s  %s\n", name.c_str(), format_duration(seconds).c_str(), outputs.c_str());
  std::fflush(stdout);
}

// The embedded case with its bathymetry path pointed at this run's harbour grid.
// Writes the embedded example case `case_name` (data/cases/<case_name>.toml) into `folder` with
// its bathymetry pointed at the demo's own harbour grid.
fs::path write_demo_case(const fs::path& folder, const fs::path& harbour_exr, const std::string& case_name,
                         std::string text) {
  const std::string placeholder = "\"../../demo-out/harbour/depth.exr\"";
  const auto at = text.find(placeholder);
  if (at == std::string::npos)
    throw Error("data/cases/" + case_name + ".toml",
                "no longer names ../../demo-out/harbour/depth.exr as its bathymetry",
                "keep that path in the example case (the demo substitutes its own)");
  text.replace(at, placeholder.size(), "\"" + fs::absolute(harbour_exr).string() + "\"");
  const fs::path case_file = folder / (case_name + ".toml");
  write_text_atomically(case_file, text);
  return case_file;
}

bake::BakeSummary bake_demo_case(const fs::path& case_file, const fs::path& bake_folder) {
  const bake::BakeCase bake_case = bake::read_bake_case(case_file);
  // What the harbour's structures became (their reflection, fitted in the model's flume).
  if (const std::string structures = bake::describe_structure_layers(bake_case.structure_layers); !structures.empty())
    std::fprintf(stderr, "%s\n", structures.c_str());
  for (const std::string& warning : bake_case.warnings) std::fprintf(stderr, "warning: %s\n", warning.c_str());
  bake::BakeOptions bake_options;
  bake_options.output_folder = bake_folder;
  bake_options.resume = fs::exists(bake::checkpoint_path(bake_folder));  // an interrupted demo continues
  bake_options.overwrite = !bake_options.resume;  // a finished demo is baked again: the demo owns its folder
  return bake::run_bake(bake_case, bake_options);
}

void run_demo(const DemoOptions& options) {
  // The last stage draws a screenshot through OpenGL: say so now, not after minutes of baking.
  if (!std::getenv("DISPLAY"))
    throw Error("nearshore demo", "needs an X display for its last stage (the playback screenshot) and none is set",
                "run it under Xvfb: xvfb-run -a nearshore demo -o demo-out");
  const fs::path out = options.output_folder;
  const fs::path chart_folder = out / "chart", harbour_folder = out / "harbour", bake_folder = out / "bake",
                 loops_folder = out / "loops", screenshot = out / "screenshot.png",
                 irregular_bake_folder = out / "bake-irregular",
                 irregular_loops_folder = out / "loops-irregular";
  create_output_folder(out);
  std::printf("%-9s %10s  %s\n", "stage", "time", "outputs");

  bathymetry::DemoHarbourFiles chart;
  run_stage("chart", [&] {
    chart = bathymetry::write_demo_harbour(chart_folder);
    return fmt::format("{}/ (depth.tif, coastline, land, structures .geojson, surroundings.tif)", chart_folder.string());
  });

  run_stage("bathy", [&] {
    bathymetry::BathyRequest request;
    // surroundings.tif last (the survey wins inside the site), the grid over the site alone: the
    // coarse ground beyond it becomes the grid's surroundings (harbour_builder.hpp step 8).
    request.inputs = {chart.depth_geotiff, chart.structures_geojson, chart.land_geojson,
                      chart.coastline_geojson, chart.surroundings_geotiff};
    request.bbox_projected_m = chart.site_box_m;
    request.spacing_m = options.spacing_m;
    const bathymetry::BathyResult result = bathymetry::build_harbour_grid(request);
    bathymetry::write_bathymetry_outputs(harbour_folder, result);
    return fmt::format("{}/ ({} x {} cells at {} m; preview.png)", harbour_folder.string(),
                       result.grid.geometry.columns, result.grid.geometry.rows,
                       result.grid.geometry.spacing_m);
  });

  bake::BakeSummary baked;
  run_stage("bake", [&] {
    baked = bake_demo_case(write_demo_case(out, harbour_folder / "depth.exr", "harbour", kDemoHarbourCase),
                           bake_folder);
    return fmt::format("{}/ ({} frames every {} s, loop period {} s; {:.3g} cell-updates/s; gauges.csv)",
                       bake_folder.string(), baked.frames, baked.frame_interval_s, baked.loop_period_s,
                       baked.cell_updates_per_s);
  });

  loops::LoopsReport report;
  run_stage("loops", [&] {
    loops::LoopsOptions loops_options;
    report = loops::analyse_loops(bake_folder, loops_options);
    loops::write_loops_pictures(report, loops_folder);
    write_text_atomically(loops_folder / "loops_report.json", report.to_json().dump(2));
    const double period_seam = report.period ? report.period->worst_seam_ratio_after : -1.0;
    return fmt::format(
        "{}/ (period loop seam ratio R = {:.3g}; {} usable transitions; loops.json in the bake)",
        loops_folder.string(), period_seam, report.usable_jumps);
  });

  // The same swell without time-periodic forcing: loops must be found by matching frames.
  run_stage("irregular", [&] {
    const bake::BakeSummary irregular = bake_demo_case(
        write_demo_case(out, harbour_folder / "depth.exr", "harbour_irregular", kDemoIrregularCase),
        irregular_bake_folder);
    loops::LoopsOptions loops_options;
    loops_options.report_lengths_s = {30, 60, 120};
    const loops::LoopsReport irregular_report = loops::analyse_loops(irregular_bake_folder, loops_options);
    loops::write_loops_pictures(irregular_report, irregular_loops_folder);
    write_text_atomically(irregular_loops_folder / "loops_report.json", irregular_report.to_json().dump(2));
    std::string best = "no loop of 60 s or more";
    double best_seam = 0;
    for (const loops::LoopReport& loop : irregular_report.best_by_length)
      if (loop.length_s >= 60 && (best_seam == 0 || loop.worst_seam_ratio_after < best_seam)) {
        best_seam = loop.worst_seam_ratio_after;
        best = fmt::format("best loop of 60 s or more: {:.1f} s, seam ratio R = {:.2f} after crossfade",
                           loop.length_s, best_seam);
      }
    return fmt::format("{}/, {}/ ({} frames, not periodic; {})", irregular_bake_folder.string(),
                       irregular_loops_folder.string(), irregular.frames, best);
  });

  run_stage("play", [&] {
    // As `nearshore play demo-out/bake --frames 15 --screenshot ...` does: the streaming engine plays
    // the loop the inspector wrote into loops.json inside the bake's own deep water.
    return write_playback_screenshot(bake_folder, screenshot, 1280, 720);
  });
}

}  // namespace

void add_demo_command(CLI::App& app) {
  auto options = std::make_shared<DemoOptions>();
  CLI::App* demo = app.add_subcommand(
      "demo", "Generate the demo harbour and run chart -> bathymetry -> bake -> loops -> screenshot");
  demo->add_option("-o,--output", options->output_folder, "Folder for every output of the demo")
      ->capture_default_str();
  // The demo site is 1.6 km x 1.2 km and its case resamples to 8 m for the bake: 2 m cells are
  // 480,000 of them, 50 m cells barely draw the 140 m entrance.
  demo->add_option("--spacing", options->spacing_m, "Harbour grid cell size, metres")
      ->capture_default_str()
      ->check(number_in(at_least(2), at_most(50)));
  set_example(*demo, "xvfb-run -a nearshore demo -o demo-out");
  demo->callback([options] { run_demo(*options); });
}

}  // namespace nearshore::tools
