// nearshore export SEQ --to FORMAT -o DIR: a baked sequence as files GIS, ocean and VFX tools open
// (docs/commands/export.md). Thin: parse options, call nearshore::exports::export_sequence, print.
#include <fmt/core.h>

#include <cstdio>
#include <memory>
#include <string>

#include "command_support.hpp"
#include "nearshore/core/progress.hpp"
#include "nearshore/export/export_sequence.hpp"

namespace nearshore::tools {
namespace {

// "a:b" (frames a .. b-1), "a:" (a to the end), ":b", or "a" (one frame): Python's slice syntax.
exports::FrameRange parse_frames(const std::string& text) {
  const auto colon = text.find(':');
  auto number = [&](const std::string& part, int empty_value) {
    if (part.empty()) return empty_value;
    std::size_t used = 0;
    const int value = std::stoi(part, &used);
    if (used != part.size() || value < 0) throw std::invalid_argument(part);
    return value;
  };
  try {
    if (colon == std::string::npos) {
      const int frame = number(text, -1);
      if (frame < 0) throw std::invalid_argument(text);
      return {frame, frame + 1};
    }
    return {number(text.substr(0, colon), 0), number(text.substr(colon + 1), -1)};
  } catch (const std::exception&) {
    throw CLI::ValidationError("--frames", "'" + text + "' is not FIRST:END (frames FIRST .. END-1, e.g. 0:100)");
  }
}

std::string size_text(double bytes) {
  if (bytes >= 1e9) return fmt::format("{:.2f} GB", bytes / 1e9);
  if (bytes >= 1e6) return fmt::format("{:.1f} MB", bytes / 1e6);
  return fmt::format("{:.1f} kB", bytes / 1e3);
}

// The agitation export's numbers: the incident Hs and where it came from, and the berths.
void print_agitation(const nlohmann::json& agitation) {
  std::printf("  incident Hs %.3f m (%s)\n", agitation["incident_significant_wave_height_m"].get<double>(),
              agitation["incident_source"].get<std::string>().c_str());
  std::printf("  Hs: %s\n", agitation["significant_wave_height_source"].get<std::string>().c_str());
  if (agitation["berths"].empty()) return;
  std::printf("  %-20s %10s %10s %8s %10s\n", "berth", "x (m)", "y (m)", "Hs (m)", "Hs/Hs_inc");
  for (const nlohmann::json& berth : agitation["berths"])
    std::printf("  %-20s %10.1f %10.1f %8.3f %10.3f\n", berth["name"].get<std::string>().c_str(), berth["x_m"].get<double>(),
                berth["y_m"].get<double>(), berth["significant_wave_height_m"].get<double>(),
                berth["agitation_coefficient"].get<double>());
}

}  // namespace

void add_export_command(CLI::App& app) {
  struct Options {
    std::string sequence, output, format, frames, berths;
    double incident_hs_m = 0.0;
    bool json = false;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand(
      "export", "Write a baked sequence as files GIS, ocean and VFX tools open (NetCDF, GeoTIFF, EXR, VDB)");
  command->add_option("sequence", options->sequence, "The sequence folder written by `nearshore bake -o DIR`")
      ->required();
  command
      ->add_option("--to", options->format,
                   "netcdf: CF-1.8 NetCDF of every frame (QGIS, xarray, Panoply); geotiff: Hs, mean level and "
                   "breaking fraction GeoTIFF and an Hs map PNG; exr-displacement: per-frame RGB displacement EXRs (Blender, Houdini, "
                   "Nuke); vdb: per-frame height-field VDBs; agitation: Hs / incident Hs GeoTIFF and map, values at --berths")
      ->required()
      ->check(CLI::IsMember({"netcdf", "geotiff", "exr-displacement", "vdb", "agitation"}));
  command->add_option("-o,--output", options->output, "Output folder (created; files of the same names are replaced)")
      ->required();
  command->add_option("--frames", options->frames,
                      "FIRST:END exports frames FIRST .. END-1 (either may be left out: 100: or :50); default all");
  command->add_flag("--json", options->json, "No progress bar; print a JSON summary (files and sizes) on stdout");
  command
      ->add_option("--incident-hs", options->incident_hs_m,
                   "agitation: the incident significant wave height, m (default: the wave maker's, from the manifest)")
      ->check(number_in(above(0), at_most(30)));
  command->add_option("--berths", options->berths,
                      "agitation: berths to read the map at: CSV name,x_m,y_m (metres from the grid's south-west corner) "
                      "or name,longitude,latitude, or GeoJSON points with a name; writes berths.csv");
  set_example(*command, "nearshore export demo-out/bake --to netcdf -o demo-out/export");
  // The sequence reader's messages name the bake's parameters; users set them with the bake's flags.
  const FlagTable flags = {{"ExportRequest::frames", "--frames"},
                           {"ExportRequest::format", "--to"},
                           {"ExportRequest::output_folder", "-o"},
                           {"ExportRequest::sequence_folder", "SEQ"},
                           {"AgitationOptions::incident_significant_wave_height_m", "--incident-hs"},
                           {"BakeOptions::output_folder", "nearshore bake -o"},
                           {"BakeOptions::resume", "nearshore bake --resume"}};
  command->callback(naming_flags_in_errors(flags, [options]() {
    if (options->json) ProgressBar::set_quiet(true);
    exports::ExportRequest request;
    request.sequence_folder = options->sequence;
    request.output_folder = options->output;
    request.format = exports::parse_export_format(options->format);
    if (!options->frames.empty()) request.frames = parse_frames(options->frames);
    if (options->incident_hs_m > 0.0) request.agitation.incident_significant_wave_height_m = options->incident_hs_m;
    request.agitation.berths_file = options->berths;
    if (request.format != exports::ExportFormat::kAgitation && (options->incident_hs_m > 0.0 || !options->berths.empty()))
      throw CLI::ValidationError("--incident-hs/--berths", "belong to --to agitation");
    const exports::ExportSummary summary = exports::export_sequence(request);
    if (options->json) {
      std::printf("%s\n", summary.to_json().dump(2).c_str());
      return;
    }
    std::printf("exported frames %d .. %d of %s as %s: %zu file%s, %s, in %s\n", summary.first_frame,
                summary.end_frame - 1, summary.sequence_folder.c_str(),
                std::string(exports::export_format_name(summary.format)).c_str(), summary.files.size(),
                summary.files.size() == 1 ? "" : "s", size_text(static_cast<double>(summary.total_bytes())).c_str(),
                format_duration(summary.seconds).c_str());
    if (summary.files.size() == 1)
      std::printf("  %s\n", summary.files.front().file.c_str());
    else if (!summary.files.empty())
      std::printf("  %s .. %s\n", summary.files.front().file.c_str(), summary.files.back().file.c_str());
    if (!summary.horizontal_displacement.empty())
      std::printf("  horizontal displacement: %s\n", summary.horizontal_displacement.c_str());
    if (!summary.agitation.is_null()) print_agitation(summary.agitation);
    for (const std::string& note : summary.notes) std::printf("  note: %s\n", note.c_str());
  }));
}

}  // namespace nearshore::tools
