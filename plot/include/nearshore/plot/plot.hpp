#pragma once
// nearshore_plot: pictures a person looks at: colour maps of a field (bathymetry preview, distance matrix heat
// map) and line plots with axes, legend and labels (gauge time series, model against data).
// Text is drawn with FreeType and the DejaVu font (fonts-dejavu-core), PNG files written with libpng,
// atomically. The runtime never links this library.
#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "nearshore/core/image.hpp"
#include "nearshore/core/raster.hpp"

namespace nearshore {

enum class ColourMap {
  kViridis,     ///< perceptually uniform, for magnitudes (distance matrix, wave height)
  kBathymetry,  ///< light cyan (shallow) to deep navy (deep), for depth in metres
  kDiverging,   ///< blue - white - red, for signed fields (surface elevation, signed distance)
};

/// Colour of `t` in [0, 1] (clamped) on the map.
Rgb colour_at(ColourMap map, double t);

/// A straight line of `thickness` pixels from (x0, y0) to (x1, y1) (pixels, row 0 at the top).
void draw_line(Image& image, double x0, double y0, double x1, double y1, Rgb colour, int thickness = 1);
/// Text with its baseline-left at (x, y), height `size_px` pixels (DejaVu Sans; skipped when the
/// font is missing, the picture is still written).
void draw_text(Image& image, int x, int y, const std::string& text, Rgb colour, int size_px = 14);
/// The width draw_text gives `text` at `size_px` (the sum of the glyphs' advances), pixels.
int text_width_px(const std::string& text, int size_px = 14);
/// Writes a PNG atomically; throws nearshore::Error naming the path on failure.
void write_png(const Image& image, const std::filesystem::path& path);
/// Reads a PNG (any bit depth or colour type, converted to 8-bit RGB) back into an Image, e.g. to
/// check a picture's pixels; throws nearshore::Error naming the path when it is not a readable PNG.
Image read_png(const std::filesystem::path& path);

/// The map furniture of a heat map whose field is a projected grid (issue 14 item 2: a gauge put on
/// land must show on the preview): tick marks and labels in the grid's CRS along the bottom (x) and
/// left (y) edges, a scale bar and a north arrow. Cell (i, j) covers x from origin_x_m + i *
/// cell_size_x_m, y from origin_y_m + j * cell_size_y_m (row 0 south, docs/formats.md).
struct MapAxes {
  double origin_x_m = 0.0, origin_y_m = 0.0;      ///< the field's south-west corner in the CRS
  double cell_size_x_m = 1.0, cell_size_y_m = 1.0;
  std::string x_label = "easting (m)", y_label = "northing (m)";
  /// Where true north points, degrees clockwise from the grid's +y (up): the projection's grid
  /// convergence, negated (0 on a laboratory frame or on the central meridian).
  double true_north_from_grid_deg = 0.0;
  /// "N" for true north on a chart; a laboratory frame says "+y".
  std::string north_label = "N";
};

/// The map furniture of a field on `grid`: ticks in the grid's CRS, and true north from the grid's
/// projection (GridGeometry::projection); a grid without one (a laboratory frame) gets x/y axes and
/// a "+y" arrow. The one place that derives a map's axes from a grid (bathymetry preview, the
/// export's wave-height map).
MapAxes map_axes_of(const GridGeometry& grid);

/// A raster coloured by `map` between `low` and `high`, north (last row) at the top, with a
/// colour bar and title. Cells where `mask` (if given, same size) is non-zero are drawn `mask_colour`
/// (value 2 in `second_mask_colour`, hatched, when that is set).
struct HeatMapStyle {
  std::string title;
  std::string value_label;  ///< e.g. "depth (m)"
  ColourMap map = ColourMap::kViridis;
  double low = 0.0, high = 1.0;
  int max_image_size_px = 1200;             ///< the longer side of the field area
  Rgb mask_colour = {0.55f, 0.47f, 0.36f};  ///< land brown
  /// When set, cells where `mask` is 2 (a harbour grid's kOutsideChartCell: no data) are drawn in
  /// this colour, hatched with darker diagonals; unset, they are drawn as mask_colour.
  std::optional<Rgb> second_mask_colour;
  bool first_row_at_top = false;            ///< true for matrices (row 0 = first frame at the top)
  /// Ticks in the CRS, a scale bar and a north arrow (maps; needs first_row_at_top = false).
  std::optional<MapAxes> map_axes;
};
Image render_heat_map(const Raster<float>& field, const HeatMapStyle& style,
                      const Raster<std::uint8_t>* mask = nullptr);

/// Where render_heat_map puts the field in its image, for drawing over it (coastlines, markers):
/// cell (column, row) covers x from left_px + column * pixels_per_cell, and the field's rows run
/// down from top_px (north, the last row, at the top unless first_row_at_top).
struct HeatMapPlacement {
  double left_px = 0, top_px = 0, pixels_per_cell = 1;
  int width_px = 0, height_px = 0;  ///< the field's area
  int legend_top_px = 0;            ///< the first pixel row below the field and its axis labels, free for a legend
};
HeatMapPlacement heat_map_placement(int columns, int rows, const HeatMapStyle& style);

struct PlotSeries {
  std::string label;
  std::vector<double> x, y;
  Rgb colour = {0.12f, 0.47f, 0.71f};
  bool markers_only = false;  ///< measured data as points, model as a line
};
struct LinePlot {
  std::string title, x_label, y_label;
  std::vector<PlotSeries> series;
  int width_px = 1000, height_px = 560;
};
Image render_line_plot(const LinePlot& plot);

}  // namespace nearshore
