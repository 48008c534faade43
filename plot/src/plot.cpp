#include "nearshore/plot/plot.hpp"

#include <ft2build.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include FT_FREETYPE_H
#include <fmt/core.h>
#include <png.h>

#include <cstdio>
#include <mutex>

#include "nearshore/core/atomic_file.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/core/map_projection.hpp"

namespace nearshore {
namespace {

Rgb lerp(const Rgb& a, const Rgb& b, double t) {
  return {static_cast<float>(a[0] + (b[0] - a[0]) * t), static_cast<float>(a[1] + (b[1] - a[1]) * t),
          static_cast<float>(a[2] + (b[2] - a[2]) * t)};
}

Rgb from_stops(const std::vector<Rgb>& stops, double t) {
  t = std::clamp(t, 0.0, 1.0) * (stops.size() - 1);
  const auto index = std::min<std::size_t>(static_cast<std::size_t>(t), stops.size() - 2);
  return lerp(stops[index], stops[index + 1], t - index);
}

// The DejaVu font from fonts-dejavu-core (scripts/install-deps.sh). Text is skipped (the picture
// is still written) if the font cannot be loaded. PNG and text go through libpng and FreeType
// directly, not a bigger image library: they are this small library's only dependencies.
constexpr const char* kFontPath = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";

// One FreeType face for the process, loaded on first use; FreeType faces are not thread-safe, so
// drawing text takes the lock.
struct Font {
  FT_Library library = nullptr;
  FT_Face face = nullptr;
  std::mutex mutex;
  Font() {
    if (FT_Init_FreeType(&library) != 0) return;
    if (FT_New_Face(library, kFontPath, 0, &face) != 0) face = nullptr;
  }
};
Font& font() {
  static Font instance;
  return instance;
}

// "Nice" tick spacing (1, 2, 5 x 10^k) for an axis spanning `range` with about `count` ticks.
double tick_step(double range, int count) {
  const double raw = range / std::max(count, 1);
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  for (double nice : {1.0, 2.0, 5.0, 10.0})
    if (raw <= nice * magnitude) return nice * magnitude;
  return 10.0 * magnitude;
}

std::string tick_label(double value, double step) {
  const int decimals = std::max(0, -static_cast<int>(std::floor(std::log10(step))));
  return fmt::format("{:.{}f}", std::abs(value) < 1e-12 * step ? 0.0 : value, decimals);
}

}  // namespace

Rgb colour_at(ColourMap map, double t) {
  switch (map) {
    case ColourMap::kViridis:  // sampled from matplotlib's viridis at 0, 0.25, 0.5, 0.75, 1
      return from_stops({{0.267f, 0.005f, 0.329f},
                         {0.229f, 0.322f, 0.546f},
                         {0.128f, 0.567f, 0.551f},
                         {0.369f, 0.789f, 0.383f},
                         {0.993f, 0.906f, 0.144f}},
                        t);
    case ColourMap::kBathymetry:
      return from_stops({{0.80f, 0.95f, 0.97f},
                         {0.45f, 0.78f, 0.90f},
                         {0.16f, 0.50f, 0.78f},
                         {0.05f, 0.25f, 0.55f},
                         {0.02f, 0.08f, 0.28f}},
                        t);
    case ColourMap::kDiverging:
      return from_stops({{0.02f, 0.19f, 0.58f},
                         {0.57f, 0.77f, 0.87f},
                         {0.97f, 0.97f, 0.97f},
                         {0.96f, 0.65f, 0.51f},
                         {0.65f, 0.0f, 0.15f}},
                        t);
  }
  return {0, 0, 0};
}

void draw_line(Image& image, double x0, double y0, double x1, double y1, Rgb colour, int thickness) {
  const double length = std::hypot(x1 - x0, y1 - y0);
  const int steps = std::max(1, static_cast<int>(std::ceil(length * 2)));
  const int half = thickness / 2;
  for (int s = 0; s <= steps; ++s) {
    const double t = static_cast<double>(s) / steps;
    const int x = static_cast<int>(std::lround(x0 + (x1 - x0) * t));
    const int y = static_cast<int>(std::lround(y0 + (y1 - y0) * t));
    image.fill_rectangle(x - half, y - half, x - half + thickness - 1, y - half + thickness - 1, colour);
  }
}

void draw_text(Image& image, int x, int y, const std::string& text, Rgb colour, int size_px) {
  Font& f = font();
  if (!f.face || text.empty()) return;
  std::lock_guard lock(f.mutex);
  FT_Set_Pixel_Sizes(f.face, 0, static_cast<FT_UInt>(size_px));
  int pen_x = x;
  for (unsigned char character : text) {  // ASCII labels; other bytes render as FreeType finds them
    if (FT_Load_Char(f.face, character, FT_LOAD_RENDER) != 0) continue;
    const FT_GlyphSlot glyph = f.face->glyph;
    const FT_Bitmap& bitmap = glyph->bitmap;
    for (unsigned row = 0; row < bitmap.rows; ++row)
      for (unsigned column = 0; column < bitmap.width; ++column) {
        const float coverage = bitmap.buffer[row * bitmap.pitch + column] / 255.f;
        const int px = pen_x + glyph->bitmap_left + static_cast<int>(column);
        const int py = y - glyph->bitmap_top + static_cast<int>(row);
        if (coverage <= 0.f || px < 0 || py < 0 || px >= image.width() || py >= image.height()) continue;
        const Rgb under = image.get(px, py);
        image.set(px, py,
            {under[0] + (colour[0] - under[0]) * coverage, under[1] + (colour[1] - under[1]) * coverage,
             under[2] + (colour[2] - under[2]) * coverage});
      }
    pen_x += static_cast<int>(glyph->advance.x >> 6);
  }
}

int text_width_px(const std::string& text, int size_px) {
  Font& f = font();
  if (!f.face) return 0;
  std::lock_guard lock(f.mutex);
  FT_Set_Pixel_Sizes(f.face, 0, static_cast<FT_UInt>(size_px));
  int width = 0;
  for (unsigned char character : text)
    if (FT_Load_Char(f.face, character, FT_LOAD_DEFAULT) == 0) width += static_cast<int>(f.face->glyph->advance.x >> 6);
  return width;
}

void write_png(const Image& picture, const std::filesystem::path& path) {
  const std::vector<float>& pixels = picture.pixels();
  std::vector<unsigned char> bytes(pixels.size());
  for (std::size_t i = 0; i < bytes.size(); ++i)
    bytes[i] = static_cast<unsigned char>(std::lround(std::clamp(pixels[i], 0.f, 1.f) * 255.f));
  write_file_atomically(path, [&](const std::filesystem::path& temporary) {
    // libpng's simplified API: one call writes the whole 8-bit RGB image.
    png_image image{};
    image.version = PNG_IMAGE_VERSION;
    image.width = static_cast<png_uint_32>(picture.width());
    image.height = static_cast<png_uint_32>(picture.height());
    image.format = PNG_FORMAT_RGB;
    if (!png_image_write_to_file(&image, temporary.c_str(), 0, bytes.data(), 0, nullptr))
      throw Error(path.string(), std::string("writing PNG failed: ") + image.message,
                  "check the folder exists and is writable, and that the disk has space");
  });
}

Image read_png(const std::filesystem::path& path) {
  // libpng's simplified API converts any PNG to 8-bit RGB on read.
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&image, path.c_str()))
    throw Error(path.string(), std::string("is not a readable PNG: ") + image.message,
                "check that the file exists and was written completely");
  image.format = PNG_FORMAT_RGB;
  std::vector<unsigned char> bytes(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, bytes.data(), 0, nullptr))
    throw Error(path.string(), std::string("decoding the PNG failed: ") + image.message,
                "check that the file was written completely");
  Image picture(static_cast<int>(image.width), static_cast<int>(image.height));
  for (int y = 0; y < picture.height(); ++y)
    for (int x = 0; x < picture.width(); ++x) {
      const std::size_t at = (static_cast<std::size_t>(y) * picture.width() + x) * 3;
      picture.set(x, y, {bytes[at] / 255.f, bytes[at + 1] / 255.f, bytes[at + 2] / 255.f});
    }
  return picture;
}

// True north from the projection's grid convergence at the grid's centre (the bearing of a step
// due north, seen in the grid; UTM's convergence reaches about 2 degrees at a zone's edge at mid
// latitudes), issue 14 item 2.
MapAxes map_axes_of(const GridGeometry& grid) {
  MapAxes axes;
  axes.origin_x_m = grid.origin_x_m;
  axes.origin_y_m = grid.origin_y_m;
  axes.cell_size_x_m = grid.spacing_x_m();
  axes.cell_size_y_m = grid.spacing_y_m();
  if (grid.projection.is_null() || grid.projection.empty()) {
    axes.north_label = "+y";
    axes.x_label = "x (m)";
    axes.y_label = "y (m)";
    return axes;
  }
  const MapProjection projection = MapProjection::from_json(grid.projection, "the grid's projection");
  const ProjectedPoint centre{grid.origin_x_m + grid.width_m() / 2, grid.origin_y_m + grid.height_m() / 2};
  const LonLat place = projection.reverse(centre);
  const ProjectedPoint north = projection.forward({place.longitude_deg, place.latitude_deg + 0.01});
  axes.true_north_from_grid_deg = std::atan2(north.x_m - centre.x_m, north.y_m - centre.y_m) * 180.0 / M_PI;
  axes.x_label = "easting (m), " + projection.describe();
  return axes;
}

namespace {
constexpr int kHeatMapMargin = 50, kHeatMapBarWidth = 24, kHeatMapRight = 110;
// With map axes: room for the northing labels on the left and the easting labels and the axis
// title below the field.
constexpr int kMapAxesLeft = 100, kMapAxesBelow = 48;

// Tick labels of map coordinates: whole metres with thin-space thousands ("541 200"), so a UTM
// easting reads as the chart prints it.
std::string map_tick_label(double value_m, double step_m) {
  if (step_m < 1.0) return tick_label(value_m, step_m);
  const long long whole = std::llround(value_m);
  std::string digits = std::to_string(std::llabs(whole)), grouped;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) grouped += ' ';
    grouped += digits[i];
  }
  return (whole < 0 ? "-" : "") + grouped;
}

// The scale bar's length: the largest 1, 2 or 5 x 10^k metres not longer than a fifth of the field.
double scale_bar_length_m(double field_width_m) {
  const double limit = field_width_m / 5.0;
  const double magnitude = std::pow(10.0, std::floor(std::log10(limit)));
  double best = magnitude;
  for (double nice : {1.0, 2.0, 5.0})
    if (nice * magnitude <= limit) best = nice * magnitude;
  return best;
}

std::string length_label(double metres) {
  if (metres >= 1000.0) return fmt::format("{:g} km", metres / 1000.0);
  if (metres >= 1.0) return fmt::format("{:g} m", metres);
  return fmt::format("{:g} cm", metres * 100.0);
}

void draw_map_axes(Image& image, const HeatMapPlacement& placement, int columns, int rows, const MapAxes& axes) {
  const Rgb ink = {0.1f, 0.1f, 0.1f}, white = {1.f, 1.f, 1.f};
  const double left = placement.left_px, top = placement.top_px;
  const double right = left + placement.width_px, bottom = top + placement.height_px;
  const double width_m = columns * axes.cell_size_x_m, height_m = rows * axes.cell_size_y_m;
  const double px_per_m_x = placement.width_px / width_m, px_per_m_y = placement.height_px / height_m;
  draw_line(image, left, bottom, right, bottom, ink);
  draw_line(image, left, top, left, bottom, ink);
  // Ticks at round CRS values (not at round offsets from the corner), as a chart's graticule.
  const double x_step = tick_step(width_m, 6), y_step = tick_step(height_m, 6);
  const double x_end = axes.origin_x_m + width_m, y_end = axes.origin_y_m + height_m;
  for (double x = std::ceil(axes.origin_x_m / x_step) * x_step; x <= x_end + 1e-9 * x_step; x += x_step) {
    const double px = left + (x - axes.origin_x_m) * px_per_m_x;
    draw_line(image, px, bottom, px, bottom + 5, ink);
    const std::string label = map_tick_label(x, x_step);
    draw_text(image, static_cast<int>(px) - static_cast<int>(3.5 * label.size()), static_cast<int>(bottom) + 19, label,
              ink, 12);
  }
  for (double y = std::ceil(axes.origin_y_m / y_step) * y_step; y <= y_end + 1e-9 * y_step; y += y_step) {
    const double py = bottom - (y - axes.origin_y_m) * px_per_m_y;
    draw_line(image, left - 5, py, left, py, ink);
    const std::string label = map_tick_label(y, y_step);
    draw_text(image, static_cast<int>(left) - 8 - static_cast<int>(7 * label.size()), static_cast<int>(py) + 4, label,
              ink, 12);
  }
  draw_text(image, static_cast<int>(left + placement.width_px / 2) - text_width_px(axes.x_label, 13) / 2,
            static_cast<int>(bottom) + 37, axes.x_label, ink, 13);
  draw_text(image, 4, static_cast<int>(top) - 6, axes.y_label, ink, 13);
  // Scale bar, lower left inside the field on a white plate, alternating black and white halves.
  const double bar_m = scale_bar_length_m(width_m), bar_px = bar_m * px_per_m_x;
  if (bar_px >= 20 && placement.height_px >= 60) {
    const int x0 = static_cast<int>(left) + 10, y0 = static_cast<int>(bottom) - 30;
    image.fill_rectangle(x0 - 6, y0 - 18, x0 + static_cast<int>(bar_px) + 8, y0 + 12, white);
    image.fill_rectangle(x0, y0, x0 + static_cast<int>(bar_px / 2), y0 + 5, ink);
    draw_line(image, x0, y0, x0 + bar_px, y0, ink);
    draw_line(image, x0, y0 + 5, x0 + bar_px, y0 + 5, ink);
    draw_line(image, x0 + bar_px, y0, x0 + bar_px, y0 + 5, ink);
    draw_text(image, x0, y0 - 4, "0", ink, 11);
    const std::string label = length_label(bar_m);
    draw_text(image, x0 + static_cast<int>(bar_px) - static_cast<int>(6 * label.size()) + 4, y0 - 4, label, ink, 11);
  }
  // North arrow, upper right inside the field: an arrow turned by the grid convergence.
  if (placement.width_px >= 80 && placement.height_px >= 80) {
    const double cx = right - 28, cy = top + 38, length = 22;
    const double a = axes.true_north_from_grid_deg * M_PI / 180.0;
    const double dx = std::sin(a), dy = -std::cos(a);  // image y runs down
    image.fill_rectangle(static_cast<int>(cx) - 20, static_cast<int>(cy) - 36, static_cast<int>(cx) + 20,
                         static_cast<int>(cy) + 36, white);
    const double tip_x = cx + dx * length, tip_y = cy + dy * length, tail_x = cx - dx * length * 0.8,
                 tail_y = cy - dy * length * 0.8;
    draw_line(image, tail_x, tail_y, tip_x, tip_y, ink, 2);
    for (double side : {-1.0, 1.0}) {
      const double bx = tip_x - dx * 9 + side * -dy * 5, by = tip_y - dy * 9 + side * dx * 5;
      draw_line(image, tip_x, tip_y, bx, by, ink, 2);
    }
    // Centred under the arrow's tail, clear of it (a "+y" drawn across the shaft was unreadable).
    draw_text(image, static_cast<int>(tail_x) - text_width_px(axes.north_label, 13) / 2, static_cast<int>(tail_y) + 15,
              axes.north_label, ink, 13);
  }
}
}  // namespace

HeatMapPlacement heat_map_placement(int columns, int rows, const HeatMapStyle& style) {
  HeatMapPlacement placement;
  placement.pixels_per_cell = std::min(1.0 * style.max_image_size_px / std::max({columns, rows, 1}), 8.0);
  placement.left_px = style.map_axes ? kMapAxesLeft : kHeatMapMargin / 2;
  placement.top_px = kHeatMapMargin;
  placement.width_px = std::max(1, static_cast<int>(columns * placement.pixels_per_cell));
  placement.height_px = std::max(1, static_cast<int>(rows * placement.pixels_per_cell));
  placement.legend_top_px =
      static_cast<int>(placement.top_px) + placement.height_px + (style.map_axes ? kMapAxesBelow : 0) + 8;
  return placement;
}

Image render_heat_map(const Raster<float>& field, const HeatMapStyle& style,
                      const Raster<std::uint8_t>* mask) {
  if (field.empty()) throw Error("heat map '" + style.title + "'", "the field is empty");
  const HeatMapPlacement placement = heat_map_placement(field.columns(), field.rows(), style);
  const double scale = placement.pixels_per_cell;
  const int field_w = placement.width_px, field_h = placement.height_px;
  const int margin = kHeatMapMargin, bar_w = kHeatMapBarWidth, right = kHeatMapRight;
  const int field_left = static_cast<int>(placement.left_px);
  const int below = style.map_axes ? kMapAxesBelow : 0;
  // Wide enough for the colour bar's label written under it (a long "surface elevation (m)" ran off
  // the right edge of a narrow map).
  const int bar_label_right = field_left + field_w + 20 + text_width_px(style.value_label) + 8;
  Image image(std::max(field_left + field_w + margin / 2 + bar_w + right, bar_label_right), field_h + 2 * margin + below);
  const double span = style.high - style.low == 0 ? 1.0 : style.high - style.low;
  for (int py = 0; py < field_h; ++py) {
    int row = std::min(field.rows() - 1, static_cast<int>(py / scale));
    if (!style.first_row_at_top) row = field.rows() - 1 - row;
    for (int px = 0; px < field_w; ++px) {
      const int column = std::min(field.columns() - 1, static_cast<int>(px / scale));
      Rgb colour;
      if (mask && (*mask)(column, row) == 2 && style.second_mask_colour)
        // No data: grey with diagonal hatching (every 8th pixel diagonal darker), so it reads as
        // "nothing known here" and not as land or shallow water (issue 14 item 3).
        colour = (px + py) % 8 < 2 ? Rgb{0.45f, 0.45f, 0.45f} : *style.second_mask_colour;
      else if (mask && (*mask)(column, row))
        colour = style.mask_colour;
      else if (!std::isfinite(field(column, row)))
        colour = {1.f, 0.f, 1.f};  // NaN shows magenta, so it cannot hide
      else
        colour = colour_at(style.map, (field(column, row) - style.low) / span);
      image.set(field_left + px, margin + py, colour);
    }
  }
  const int bar_x = field_left + field_w + 20;
  for (int py = 0; py < field_h; ++py)
    image.fill_rectangle(bar_x, margin + py, bar_x + bar_w, margin + py,
                         colour_at(style.map, 1.0 - static_cast<double>(py) / std::max(1, field_h - 1)));
  const Rgb ink = {0.1f, 0.1f, 0.1f};
  draw_text(image, field_left, margin - 18, style.title, ink, 18);
  draw_text(image, bar_x + bar_w + 6, margin + 12, fmt::format("{:.4g}", style.high), ink);
  draw_text(image, bar_x + bar_w + 6, margin + field_h, fmt::format("{:.4g}", style.low), ink);
  draw_text(image, bar_x, margin + field_h + 30, style.value_label, ink);
  if (style.map_axes) {
    if (style.first_row_at_top)
      throw Error("heat map '" + style.title + "'", "has map axes but its first row at the top",
                  "draw maps with north (the last row) at the top: HeatMapStyle::first_row_at_top = false");
    draw_map_axes(image, placement, field.columns(), field.rows(), *style.map_axes);
  }
  return image;
}

Image render_line_plot(const LinePlot& plot) {
  double x_min = std::numeric_limits<double>::infinity(), x_max = -x_min, y_min = x_min, y_max = -x_min;
  for (const auto& s : plot.series)
    for (std::size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
      x_min = std::min(x_min, s.x[i]);
      x_max = std::max(x_max, s.x[i]);
      y_min = std::min(y_min, s.y[i]);
      y_max = std::max(y_max, s.y[i]);
    }
  if (!std::isfinite(x_min)) throw Error("plot '" + plot.title + "'", "has no finite data points");
  if (x_max == x_min) x_max = x_min + 1;
  if (y_max == y_min) {
    y_max += 0.5;
    y_min -= 0.5;
  }
  const double y_pad = 0.05 * (y_max - y_min);
  y_min -= y_pad;
  y_max += y_pad;
  Image image(plot.width_px, plot.height_px);
  const int left = 80, right = 30, top = 50, bottom = 60;
  const int w = plot.width_px - left - right, h = plot.height_px - top - bottom;
  auto to_px = [&](double x, double y) {
    return std::pair<double, double>{left + (x - x_min) / (x_max - x_min) * w,
                                     top + h - (y - y_min) / (y_max - y_min) * h};
  };
  const Rgb ink = {0.1f, 0.1f, 0.1f}, grid = {0.88f, 0.88f, 0.88f};
  const double x_step = tick_step(x_max - x_min, 8), y_step = tick_step(y_max - y_min, 6);
  for (double x = std::ceil(x_min / x_step) * x_step; x <= x_max + 1e-9 * x_step; x += x_step) {
    auto [px, py] = to_px(x, y_min);
    draw_line(image, px, top, px, top + h, grid);
    draw_text(image, static_cast<int>(px) - 12, top + h + 20, tick_label(x, x_step), ink, 13);
  }
  for (double y = std::ceil(y_min / y_step) * y_step; y <= y_max + 1e-9 * y_step; y += y_step) {
    auto [px, py] = to_px(x_min, y);
    draw_line(image, left, py, left + w, py, grid);
    draw_text(image, 8, static_cast<int>(py) + 5, tick_label(y, y_step), ink, 13);
  }
  draw_line(image, left, top, left, top + h, ink);
  draw_line(image, left, top + h, left + w, top + h, ink);
  for (const auto& s : plot.series) {
    for (std::size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
      auto [px, py] = to_px(s.x[i], s.y[i]);
      if (s.markers_only) {
        image.fill_rectangle(static_cast<int>(px) - 2, static_cast<int>(py) - 2, static_cast<int>(px) + 2,
                             static_cast<int>(py) + 2, s.colour);
      } else if (i > 0 && std::isfinite(s.x[i - 1]) && std::isfinite(s.y[i - 1])) {
        auto [qx, qy] = to_px(s.x[i - 1], s.y[i - 1]);
        draw_line(image, qx, qy, px, py, s.colour, 2);
      }
    }
  }
  draw_text(image, left, top - 20, plot.title, ink, 18);
  draw_text(image, left + w / 2 - 40, plot.height_px - 15, plot.x_label, ink, 14);
  draw_text(image, 8, top - 20 + 0, "", ink);
  draw_text(image, left + 8, top + 16, plot.y_label, ink, 14);
  int legend_y = top + 16;
  for (const auto& s : plot.series) {
    image.fill_rectangle(left + w - 190, legend_y - 8, left + w - 176, legend_y - 2, s.colour);
    draw_text(image, left + w - 170, legend_y, s.label, ink, 13);
    legend_y += 18;
  }
  return image;
}

}  // namespace nearshore
