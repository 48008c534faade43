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

}  // namespace

void add_export_command(CLI::App& app) {
  struct Options {
    std::string sequence, output, format, frames;
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
                   "Nuke); vdb: per-frame height-field VDBs")
      ->required()
      ->check(CLI::IsMember({"netcdf", "geotiff", "exr-displacement", "vdb"}));
  command->add_option("-o,--output", options->output, "Output folder (created; files of the same names are replaced)")
      ->required();
  command->add_option("--frames", options->frames,
                      "FIRST:END exports frames FIRST .. END-1 (either may be left out: 100: or :50); default all");
  command->add_flag("--json", options->json, "No progress bar; print a JSON summary (files and sizes) on stdout");
  set_example(*command, "nearshore export demo-out/bake --to netcdf -o demo-out/export");
  // The sequence reader's messages name the bake's parameters; users set them with the bake's flags.
  const FlagTable flags = {{"ExportRequest::frames", "--frames"},
                           {"ExportRequest::format", "--to"},
                           {"ExportRequest::output_folder", "-o"},
                           {"ExportRequest::sequence_folder", "SEQ"},
                           {"BakeOptions::output_folder", "nearshore bake -o"},
                           {"BakeOptions::resume", "nearshore bake --resume"}};
  command->callback(naming_flags_in_errors(flags, [options]() {
    if (options->json) ProgressBar::set_quiet(true);
    exports::ExportRequest request;
    request.sequence_folder = options->sequence;
    request.output_folder = options->output;
    request.format = exports::parse_export_format(options->format);
    if (!options->frames.empty()) request.frames = parse_frames(options->frames);
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
    for (const std::string& note : summary.notes) std::printf("  note: %s\n", note.c_str());
  }));
}

}  // namespace nearshore::tools
