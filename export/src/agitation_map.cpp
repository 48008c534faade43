// agitation.png: the agitation coefficient as a map a port engineer reads without a GIS: axes in the
// grid's CRS, a colour bar of Hs / incident Hs, land and no-data distinct, the structures (the porous
// layers of breakwaters and absorbing quays: water cells of porosity < 1) drawn over the field, the
// berths marked and named. Drawn by nearshore_plot as the geotiff export's Hs map is.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <fmt/core.h>

#include "export_input.hpp"
#include "nearshore/plot/plot.hpp"

namespace nearshore::exports {
namespace {

// The colour bar's top: at least 1 (the incident Hs, so a sheltered basin reads as a fraction of
// the bar), more where reflection or resonance amplify: the 99.5th percentile over the water (a few
// cells at the wave maker do not wash out the basin), rounded up to 1.25, 1.5, 2, 2.5, 3, 4 or 5.
double coefficient_bar_top(const Raster<float>& coefficient, const ExportInput& input) {
  std::vector<float> water;
  for (std::size_t cell = 0; cell < coefficient.size(); ++cell)
    if (!input.is_land(cell) && std::isfinite(coefficient.values()[cell])) water.push_back(coefficient.values()[cell]);
  if (water.empty()) return 1.0;
  const auto at = water.begin() + static_cast<std::ptrdiff_t>(0.995 * (water.size() - 1));
  std::nth_element(water.begin(), at, water.end());
  for (double nice : {1.0, 1.25, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0})
    if (nice >= *at * (1.0 - 1e-9)) return nice;
  return 5.0;
}

}  // namespace

void write_agitation_map(const ExportInput& input, const Raster<float>& coefficient, const std::string& subtitle,
                         const std::vector<BerthValue>& berths, const std::filesystem::path& path) {
  const GridGeometry& g = input.harbour.geometry;
  HeatMapStyle style;
  style.title = "agitation coefficient Hs / incident Hs";
  style.value_label = "Hs / Hs incident (-)";
  style.map = ColourMap::kViridis;
  style.low = 0.0;
  style.high = coefficient_bar_top(coefficient, input);
  style.map_axes = map_axes_of(g);
  const Rgb no_data_colour{0.78f, 0.78f, 0.78f};
  style.second_mask_colour = no_data_colour;
  Image map = render_heat_map(coefficient, style, &input.harbour.land);

  // The structures over the field: each porous water cell filled dark grey.
  const HeatMapPlacement placement = heat_map_placement(g.columns, g.rows, style);
  const Rgb structure_colour{0.25f, 0.25f, 0.28f};
  const double cell_px = placement.pixels_per_cell;
  const auto pixel_x = [&](double column) { return placement.left_px + column * cell_px; };
  const auto pixel_y = [&](double row) { return placement.top_px + (g.rows - row) * cell_px; };  // north at the top
  int structure_cells = 0;
  for (int row = 0; row < g.rows; ++row)
    for (int column = 0; column < g.columns; ++column)
      if (input.harbour.land(column, row) == kWaterCell && input.harbour.porosity(column, row) < 1.0f) {
        ++structure_cells;
        map.fill_rectangle(static_cast<int>(pixel_x(column)), static_cast<int>(pixel_y(row + 1.0)),
                           static_cast<int>(std::ceil(pixel_x(column + 1.0))) - 1,
                           static_cast<int>(std::ceil(pixel_y(row))) - 1, structure_colour);
      }

  // The berths: a white-ringed dot and the name with its coefficient.
  const Rgb ink{0.1f, 0.1f, 0.1f}, white{1.0f, 1.0f, 1.0f}, berth_colour{0.85f, 0.1f, 0.1f};
  for (const BerthValue& value : berths) {
    const double x = pixel_x(value.berth.x_m / g.spacing_x_m()), y = pixel_y(value.berth.y_m / g.spacing_y_m());
    map.fill_rectangle(static_cast<int>(x) - 4, static_cast<int>(y) - 4, static_cast<int>(x) + 4, static_cast<int>(y) + 4, white);
    map.fill_rectangle(static_cast<int>(x) - 2, static_cast<int>(y) - 2, static_cast<int>(x) + 2, static_cast<int>(y) + 2,
                       berth_colour);
    const std::string label = fmt::format("{} {:.2f}", value.berth.name, value.agitation_coefficient);
    draw_text(map, static_cast<int>(x) + 7, static_cast<int>(y) + 1, label, white, 13);
    draw_text(map, static_cast<int>(x) + 6, static_cast<int>(y), label, ink, 13);
  }

  // The legend below the field.
  const int x = static_cast<int>(placement.left_px), y = placement.legend_top_px + 14;
  map.fill_rectangle(x, y - 11, x + 20, y + 1, style.mask_colour);
  draw_text(map, x + 26, y, "land", ink, 14);
  int at = x + 70;
  if (structure_cells > 0) {
    map.fill_rectangle(at, y - 11, at + 20, y + 1, structure_colour);
    draw_text(map, at + 26, y, "structure (porous layer)", ink, 14);
    at += 210;
  }
  map.fill_rectangle(at, y - 11, at + 20, y + 1, no_data_colour);
  draw_line(map, at, y + 1, at + 12, y - 11, Rgb{0.45f, 0.45f, 0.45f}, 1);
  draw_text(map, at + 26, y, "no data (outside the chart)", ink, 14);
  if (!berths.empty()) {
    at += 230;
    map.fill_rectangle(at + 6, y - 9, at + 14, y - 1, berth_colour);
    draw_text(map, at + 26, y, "berth (name, Hs / Hs incident)", ink, 14);
  }
  draw_text(map, x, y + 20, subtitle, ink, 13);
  write_png(map, path);
}

}  // namespace nearshore::exports
