// nearshore bathy: chart data in, solver-ready harbour grid out (docs/commands/bathy.md).
// Thin: parse options, call nearshore::bathymetry::build_harbour_grid, write, print.
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <fmt/core.h>

#include "command_support.hpp"
#include "nearshore/bathymetry/harbour_builder.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/core/geo_position.hpp"
#include "nearshore/core/progress.hpp"

namespace nearshore::tools {
namespace {

std::array<double, 4> parse_box(const std::string& text) {
  std::array<double, 4> box{};
  char extra = 0;
  if (std::sscanf(text.c_str(), "%lf,%lf,%lf,%lf%c", &box[0], &box[1], &box[2], &box[3], &extra) != 4)
    throw std::invalid_argument(text);
  return box;
}

// --bbox LON0,LAT0,LON1,LAT1 (degrees) and --bbox-m X0,Y0,X1,Y1 (metres): four finite numbers, the
// first corner south-west of the second, degrees within the globe. Checked while parsing, like
// every number on the command line (number_in).
CLI::Validator box_check(bool degrees) {
  const std::string example = degrees ? "-122.46,47.25,-122.40,47.29" : "540000,5232000,545000,5236000";
  return CLI::Validator(
      [degrees, example](std::string& text) -> std::string {
        std::array<double, 4> b{};
        try {
          b = parse_box(text);
        } catch (const std::invalid_argument&) {
          return "'" + text + "' is not four numbers separated by commas, e.g. " + example;
        }
        for (double v : b)
          if (!std::isfinite(v)) return text + " holds a number that is not finite";
        if (!(b[0] < b[2] && b[1] < b[3]))
          return text + " is empty or reversed: the first corner must be south-west of the second (x0 < x1, y0 < y1)";
        if (degrees && (b[0] < -180 || b[2] > 180 || b[1] < -90 || b[3] > 90))
          return text + " is outside the globe: longitudes in [-180, 180], latitudes in [-90, 90]";
        return {};
      },
      degrees ? "LON0,LAT0,LON1,LAT1" : "X0,Y0,X1,Y1");
}

// --structure NAME=WIDTH:POROSITY, e.g. breakwater=25:0.4
std::pair<std::string, bathymetry::StructureStyle> parse_structure(const std::string& text) {
  const auto equals = text.find('='), colon = text.find(':');
  if (equals == std::string::npos || equals == 0 || colon == std::string::npos || colon < equals)
    throw std::invalid_argument(text);
  bathymetry::StructureStyle style;
  std::size_t used = 0;
  const std::string width = text.substr(equals + 1, colon - equals - 1), porosity = text.substr(colon + 1);
  style.crest_width_m = std::stod(width, &used);
  if (used != width.size()) throw std::invalid_argument(text);
  style.porosity = std::stod(porosity, &used);
  if (used != porosity.size()) throw std::invalid_argument(text);
  return {text.substr(0, equals), style};
}

CLI::Validator structure_check() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        bathymetry::StructureStyle style;
        try {
          style = parse_structure(text).second;
        } catch (const std::logic_error&) {
          return "'" + text + "' is not NAME=WIDTH_M:POROSITY, e.g. breakwater=25:0.4";
        }
        if (!(std::isfinite(style.crest_width_m) && style.crest_width_m > 0))
          return text + ": the crest width must be a finite number of metres > 0";
        if (!(style.porosity >= 0 && style.porosity <= 1))
          return text + ": the porosity must be in [0, 1] (0 a vertical wall, 0.3-0.5 rubble mound, 1 transparent)";
        return {};
      },
      "NAME=WIDTH_M:POROSITY");
}

// The flag of each parameter that library errors may name (command_support.hpp), as the options
// below set them: BathyRequest, and the ReadOptions build_harbour_grid passes on to read_source.
FlagTable bathy_flags() {
  return {{"BathyRequest::spacing_m", "--spacing"},
          {"BathyRequest::bbox_lon_lat", "--bbox"},
          {"BathyRequest::bbox_projected_m", "--bbox-m"},
          {"BathyRequest::sign", "--sign"},
          {"ReadOptions::sign", "--sign"},
          {"DepthSign::kPositiveDown", "--sign depth"},
          {"DepthSign::kPositiveUp", "--sign elevation"},
          {"BathyRequest::text_crs", "--xyz-crs"},
          {"ReadOptions::text_crs", "--xyz-crs"},
          {"BathyRequest::projection", "--projection"},
          {"BathyRequest::structure_styles", "--structure NAME=WIDTH_M:POROSITY"},
          {"BathyRequest::water_level_m", "--water-level"},
          {"BathyRequest::minimum_depth_m", "--min-depth"},
          {"BathyRequest::maximum_slope", "--max-slope"},
          {"BathyRequest::land_elevation_m", "--land-elevation"},
          {"BathyRequest::fill_uncovered_from_nearest", "--fill-uncovered"},
          {"BathyRequest::coastline_band_m", "--coastline-band"},
          {"BathyRequest::leave_one_out", "--leave-one-out"},
          {"BathyRequest::surroundings_margin_m", "--surroundings-margin"},
          {"write_bathymetry_outputs(folder)", "-o"}};
}

}  // namespace

void add_bathy_command(CLI::App& app) {
  struct Options {
    std::vector<std::string> inputs;
    double spacing_m = 10.0;
    std::string bbox, bbox_m, sign = "auto", projection = "utm", output, xyz_crs;
    std::vector<std::string> structures;
    double water_level_m = 0.0, minimum_depth_m = 0.5, maximum_slope = 0.0, land_elevation_m = 2.0, band_m = 200.0;
    double surroundings_margin_m = -1.0;  // the grid's longer side
    bool json = false, leave_one_out = false, fill_uncovered = false;
    std::vector<std::string> marks;  // NAME:POSITION, drawn on the preview
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand("bathy", "Turn chart data into a solver-ready harbour grid");
  command->add_option("inputs", options->inputs,
                      "Charts (S-57 .000, updates applied), depth rasters (GeoTIFF, NetCDF, ESRI ASCII), vector files "
                      "(GeoJSON coastline/land/breakwaters) and soundings (.xyz/.csv: x y depth); highest priority first")
      ->required();
  command->add_option("--spacing", options->spacing_m, "Cell size in metres")
      ->required()
      ->check(number_in(above(0), at_most(100000)));
  command->add_option("--bbox", options->bbox, "Area as LON0,LAT0,LON1,LAT1 (WGS 84 degrees); default: all the data")
      ->check(box_check(true));
  command->add_option("--bbox-m", options->bbox_m, "Area as X0,Y0,X1,Y1 in metres of the chosen projection")
      ->check(box_check(false));
  command->add_option("-o,--output", options->output, "Output folder (depth.tif, depth.exr, coastline.vdb, preview.png, summary.json)")
      ->required();
  command->add_option("--sign", options->sign, "Sign of raster and text values: auto (from metadata), depth (positive down), elevation (positive up)")
      ->check(CLI::IsMember({"auto", "depth", "elevation"}));
  command->add_option("--projection", options->projection, "utm (zone of the area), utm:10N (given zone), or local-tm");
  command->add_option("--xyz-crs", options->xyz_crs, "CRS of projected x y in text soundings, e.g. EPSG:32610 (default lon lat)");
  command->add_option("--structure", options->structures,
                      "Porosity band of a structure category, NAME=WIDTH_M:POROSITY (breakwater, groyne, mole, pier, quay, "
                      "sea_wall, riprap, revetment, training_wall, or a GeoJSON category); repeatable")
      ->check(structure_check());
  command->add_option("--water-level", options->water_level_m,
                      "Still water in metres above the sounding datum (e.g. mean sea level over MLLW); default 0")
      ->check(number_in(at_least(-100), at_most(100)));
  command->add_option("--min-depth", options->minimum_depth_m, "Water shallower than this (m) is deepened to it")
      ->check(number_in(at_least(0), at_most(1000)));
  command->add_option("--max-slope", options->maximum_slope, "Smooth the sea bed where |grad d| exceeds this (0 = off)")
      ->check(number_in(at_least(0), at_most(100)));
  command->add_option("--land-elevation", options->land_elevation_m, "Elevation (m) of land cells where no input gives one")
      ->check(number_in(above(0), at_most(10000)));
  command->add_option("--coastline-band", options->band_m, "Half-width (m) of the narrow band stored in coastline.vdb")
      ->check(number_in(above(0), at_most(100000)));
  command->add_flag("--fill-uncovered", options->fill_uncovered,
                    "Cells no input covers take the nearest covered depth (default: they are no data, outside the chart; the bake's [bathymetry] outside_chart decides)");
  command->add_flag("--leave-one-out", options->leave_one_out, "Cross-validate: re-grid each chart sounding from the others");
  command->add_option("--surroundings-margin", options->surroundings_margin_m,
                      "How far (m) the surroundings (the coarse ground round the grid the renderer draws beyond it) reach "
                      "beyond the grid on every side; 0: none (default: the grid's longer side)")
      ->check(number_in(at_least(0), at_most(1e6)));
  command->add_option("--mark", options->marks,
                      "Draw a named place on the preview, NAME:POSITION with POSITION as lat=..,lon=.., "
                      "easting_m=..,northing_m=.. (the grid's CRS) or X,Y from the grid's south-west corner; repeatable "
                      "(e.g. a case file's gauges)");
  command->add_flag("--json", options->json, "Print summary.json instead of the short report");
  set_example(*command, "nearshore bathy ../shared/charts/tacoma_us5wa22m/US5WA22M.000 --spacing 10 -o out/tacoma");
  command->callback(naming_flags_in_errors(bathy_flags(), [options]() {
    bathymetry::BathyRequest request;
    for (const auto& input : options->inputs) request.inputs.emplace_back(input);
    request.spacing_m = options->spacing_m;
    if (!options->bbox.empty()) request.bbox_lon_lat = parse_box(options->bbox);  // checked: box_check
    if (!options->bbox_m.empty()) request.bbox_projected_m = parse_box(options->bbox_m);
    request.sign = options->sign == "depth"       ? bathymetry::DepthSign::kPositiveDown
                   : options->sign == "elevation" ? bathymetry::DepthSign::kPositiveUp
                                                  : bathymetry::DepthSign::kAuto;
    request.projection = options->projection;
    request.text_crs = options->xyz_crs;
    for (const auto& text : options->structures) {
      const auto [name, style] = parse_structure(text);  // checked while parsing: structure_check
      request.structure_styles[name] = style;
    }
    request.water_level_m = options->water_level_m;
    request.minimum_depth_m = options->minimum_depth_m;
    request.maximum_slope = options->maximum_slope;
    request.land_elevation_m = options->land_elevation_m;
    request.coastline_band_m = options->band_m;
    request.leave_one_out = options->leave_one_out;
    request.fill_uncovered_from_nearest = options->fill_uncovered;
    request.surroundings_margin_m = options->surroundings_margin_m;
    if (options->json) ProgressBar::set_quiet(true);
    const bathymetry::BathyResult result = bathymetry::build_harbour_grid(request);
    // Marks are placed through the one position parser (core/geo_position.hpp), as the bake
    // places a case's gauges, so the preview shows where the bake will put them.
    std::vector<bathymetry::PreviewMark> marks;
    for (const std::string& text : options->marks) {
      const auto colon = text.find(':');
      if (colon == std::string::npos || colon == 0)
        throw Error("--mark " + text, "has no name", "write NAME:POSITION, e.g. thea_foss:lat=47.2620,lon=-122.4383");
      const GeoPosition position = parse_geo_position(text.substr(colon + 1), "--mark " + text);
      marks.push_back({text.substr(0, colon),
                       place_in_grid(position, result.grid.geometry, "--mark " + text, "the mark")});
    }
    const nlohmann::json summary = bathymetry::write_bathymetry_outputs(options->output, result, options->band_m, marks);
    if (summary.contains("marks"))
      for (std::size_t i = result.warnings.size(); i < summary["warnings"].size(); ++i)
        std::fprintf(stderr, "warning: %s\n", summary["warnings"][i].get<std::string>().c_str());
    // Warnings go to stderr (also with --json, whose stdout stays one JSON document), named by flag.
    for (const std::string& warning : result.warnings)
      std::fprintf(stderr, "warning: %s\n", name_flags(warning, bathy_flags()).c_str());
    if (options->json) {
      std::printf("%s\n", summary.dump(2).c_str());
      return;
    }
    const auto& cells = summary["cells"];
    std::printf("%s\n", fmt::format("grid {} x {} cells at {} m in {}; water depth {:.2f} .. {:.2f} m",
                                    summary["columns"].get<int>(), summary["rows"].get<int>(), request.spacing_m,
                                    summary["crs"].get<std::string>(), summary["water_depth_m"]["min"].get<double>(),
                                    summary["water_depth_m"]["max"].get<double>()).c_str());
    std::printf("%s\n", fmt::format("cells: {} water, {} land, {} outside every input ({}), {} bounded by depth areas, "
                                    "{} clamped to {} m, {} smoothed",
                                    cells["water"].get<std::size_t>(), cells["land"].get<std::size_t>(),
                                    cells["uncovered"].get<std::size_t>(), request.fill_uncovered_from_nearest ? "filled from nearest" : "no data, outside the chart",
                                    cells["bounded_by_depth_areas"].get<std::size_t>(),
                                    summary["conditioning"]["minimum_depth_clamp"]["cells"].get<std::size_t>(),
                                    request.minimum_depth_m,
                                    summary["conditioning"]["slope_smoothing"]["cells"].get<std::size_t>()).c_str());
    if (summary.contains("leave_one_out"))
      std::printf("%s\n", fmt::format("leave-one-out over {} soundings: median |error| {:.2f} m, 90th percentile {:.2f} m",
                                      summary["leave_one_out"]["soundings"].get<std::size_t>(),
                                      summary["leave_one_out"]["median_absolute_error_m"].get<double>(),
                                      summary["leave_one_out"]["p90_absolute_error_m"].get<double>()).c_str());
    if (summary.contains("surroundings")) {
      const auto& outer = summary["surroundings"];
      std::printf("%s\n", fmt::format("surroundings {} x {} cells at {:.0f} m, {:.0f} m beyond the grid: {} water, {} land, "
                                      "{} no data (beyond every input)",
                                      outer["columns"].get<int>(), outer["rows"].get<int>(), outer["spacing_m"].get<double>(),
                                      outer["margin_m"].get<double>(), outer["cells"]["water"].get<std::size_t>(),
                                      outer["cells"]["land"].get<std::size_t>(), outer["cells"]["no_data"].get<std::size_t>())
                             .c_str());
    }
    std::printf("wrote %s/{depth.tif, depth.exr, coastline.vdb, preview.png, summary.json}\n", options->output.c_str());
  }));
}

}  // namespace nearshore::tools
