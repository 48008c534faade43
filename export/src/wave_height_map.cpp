// The geotiff export's picture: wave_statistics_hs.png, the significant wave height of
// wave_statistics.tif band 1 drawn as a map a person reads without a GIS (issue 14 item 2): axes in
// the grid's CRS, a colour bar in metres, land and no-data distinct, north arrow, scale bar, and a
// title that says which sequence and which frames were averaged. Drawn by nearshore_plot, the same
// heat map and map furniture as the bathymetry preview.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <fmt/core.h>

#include "export_input.hpp"
#include "nearshore/plot/plot.hpp"

namespace nearshore::exports {
namespace {

// The colour bar's top: the 99.5th percentile of Hs over the water, so a few extreme cells (the
// wave maker's edge, a resonant corner) do not wash out the harbour; cells above it take the top
// colour. Rounded up to a round number (1, 1.5, 2, 2.5, 3, 4, 5, 6, 8 x 10^k) so the bar's end reads
// as a chart's legend does.
double colour_bar_top_m(const Raster<float>& hs_m, const ExportInput& input) {
  std::vector<float> water;
  water.reserve(hs_m.size());
  for (std::size_t cell = 0; cell < hs_m.size(); ++cell)
    if (!input.is_land(cell) && std::isfinite(hs_m.values()[cell])) water.push_back(hs_m.values()[cell]);
  if (water.empty()) return 1.0;
  const auto at = water.begin() + static_cast<std::ptrdiff_t>(0.995 * (water.size() - 1));
  std::nth_element(water.begin(), at, water.end());
  const double top = *at;
  if (!(top > 0.0)) return 1.0;  // still water everywhere: any bar shows it as the bottom colour
  const double magnitude = std::pow(10.0, std::floor(std::log10(top)));
  for (double nice : {1.0, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 8.0, 10.0})
    if (nice * magnitude >= top * (1.0 - 1e-9)) return nice * magnitude;
  return 10.0 * magnitude;
}

// "tacoma-coarse/sequence": the sequence folder and its parent (bakes often write into "sequence").
std::string sequence_name(const std::filesystem::path& folder) {
  const std::filesystem::path normal = folder.lexically_normal();
  const std::filesystem::path last = normal.has_filename() ? normal : normal.parent_path();
  const std::string parent = last.parent_path().filename().string();
  return parent.empty() || parent == "." || parent == ".." ? last.filename().string()
                                                           : parent + "/" + last.filename().string();
}

}  // namespace

void write_wave_height_map(const ExportInput& input, const Raster<float>& hs_m, const Raster<float>& wet_fraction,
                           const FrameTimes& times, ExportSummary& summary) {
  const GridGeometry& g = input.harbour.geometry;
  const std::filesystem::path path = input.output_folder / "wave_statistics_hs.png";
  HeatMapStyle style;
  style.title = "significant wave height Hs, " + sequence_name(input.reader.folder());
  style.value_label = "Hs (m)";
  style.map = ColourMap::kViridis;
  style.low = 0.0;
  style.high = colour_bar_top_m(hs_m, input);
  style.map_axes = map_axes_of(g);
  const Rgb no_data_colour{0.78f, 0.78f, 0.78f};  // outside the chart: hatched grey, as on the bathymetry preview
  style.second_mask_colour = no_data_colour;
  Image map = render_heat_map(hs_m, style, &input.harbour.land);

  const HeatMapPlacement placement = heat_map_placement(g.columns, g.rows, style);
  // The swash: water cells dry in some frames, where the bake pins eta at -d, so 4 std. dev. of eta
  // measures the moving shoreline rather than a wave height (surface_statistics.hpp). White, which
  // viridis never reaches; a cell smaller than a pixel still takes its pixel.
  const Rgb swash_colour{1.0f, 1.0f, 1.0f};
  int swash_cells = 0;
  const double cell_px = placement.pixels_per_cell;
  for (int row = 0; row < g.rows; ++row)
    for (int column = 0; column < g.columns; ++column) {
      const std::size_t cell = static_cast<std::size_t>(row) * g.columns + column;
      if (input.is_land(cell) || !(wet_fraction.values()[cell] < 1.0f)) continue;
      ++swash_cells;
      const double left = placement.left_px + column * cell_px, top = placement.top_px + (g.rows - 1 - row) * cell_px;
      const int x0 = static_cast<int>(std::floor(left)), y0 = static_cast<int>(std::floor(top));
      map.fill_rectangle(x0, y0, std::max(x0, static_cast<int>(std::ceil(left + cell_px)) - 1),
                         std::max(y0, static_cast<int>(std::ceil(top + cell_px)) - 1), swash_colour);
    }

  // The legend below the field: what the masks are and which frames the statistics average.
  const Rgb ink{0.1f, 0.1f, 0.1f};
  const int x = static_cast<int>(placement.left_px), y = placement.legend_top_px + 14;
  map.fill_rectangle(x, y - 11, x + 20, y + 1, style.mask_colour);
  draw_text(map, x + 26, y, "land", ink, 14);
  map.fill_rectangle(x + 70, y - 11, x + 90, y + 1, no_data_colour);
  draw_line(map, x + 70, y + 1, x + 82, y - 11, Rgb{0.45f, 0.45f, 0.45f}, 1);
  draw_text(map, x + 96, y, "no data (outside the chart)", ink, 14);
  if (swash_cells > 0) {
    map.fill_rectangle(x + 310, y - 11, x + 330, y + 1, swash_colour);
    draw_line(map, x + 310, y - 11, x + 330, y - 11, ink, 1);
    draw_line(map, x + 310, y + 1, x + 330, y + 1, ink, 1);
    draw_text(map, x + 336, y, fmt::format("swash: dry part of the time ({} cells; Hs there is not a wave height)", swash_cells),
              ink, 14);
  }
  draw_text(map, x, y + 20,
            fmt::format("4 std. dev. of eta over frames {}-{}: t = {:.1f}-{:.1f} s, {:.1f} s averaged",
                        input.first_frame, input.end_frame - 1, times.first_s, times.last_s,
                        input.frame_count() * input.reader.frame_interval_s()),
            ink, 13);
  write_png(map, path);
  record_file(summary, path);
}

}  // namespace nearshore::exports
