#include "nearshore/plot/plot.hpp"

#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <cmath>

namespace fs = std::filesystem;

TEST(ColourMap, EndsAreTheDocumentedColours) {
  auto deep = nearshore::colour_at(nearshore::ColourMap::kBathymetry, 1.0);
  auto shallow = nearshore::colour_at(nearshore::ColourMap::kBathymetry, 0.0);
  EXPECT_LT(deep[0] + deep[1] + deep[2], shallow[0] + shallow[1] + shallow[2]) << "deep water is darker";
  auto white = nearshore::colour_at(nearshore::ColourMap::kDiverging, 0.5);
  EXPECT_GT(white[0], 0.9f);
}

TEST(Plot, LinePlotAndHeatMapWriteReadablePngs) {
  const fs::path folder = fs::temp_directory_path() / "nearshore_plot_test";
  fs::create_directories(folder);
  nearshore::LinePlot plot{"sine", "t (s)", "eta (m)", {}};
  nearshore::PlotSeries series{"model", {}, {}};
  for (int i = 0; i < 200; ++i) {
    series.x.push_back(i * 0.05);
    series.y.push_back(std::sin(i * 0.05));
  }
  plot.series.push_back(series);
  write_png(nearshore::render_line_plot(plot), folder / "line.png");
  nearshore::Raster<float> field(40, 30);
  for (int j = 0; j < 30; ++j)
    for (int i = 0; i < 40; ++i) field(i, j) = static_cast<float>(i + j);
  nearshore::HeatMapStyle style;
  style.title = "ramp";
  style.high = 70;
  write_png(nearshore::render_heat_map(field, style), folder / "heat.png");
  for (const char* name : {"line.png", "heat.png"}) {
    auto in = OIIO::ImageInput::open((folder / name).string());
    ASSERT_TRUE(in) << name;
    EXPECT_GT(in->spec().width, 100);
    in->close();
  }
}

// Map axes (issue 14 item 2): the ticks sit at round CRS values, not at round offsets from the
// grid's corner, so a reader can place a position given in the CRS on the preview.
TEST(Plot, MapAxesPutTicksAtRoundCoordinatesOfTheCrs) {
  nearshore::Raster<float> field(100, 60);
  for (int j = 0; j < 60; ++j)
    for (int i = 0; i < 100; ++i) field(i, j) = static_cast<float>(i);
  nearshore::HeatMapStyle style;
  style.title = "map";
  style.high = 100;
  style.max_image_size_px = 500;  // 5 px per cell
  nearshore::MapAxes axes;
  axes.origin_x_m = 541234.5;  // 100 cells of 10 m: 541234.5 .. 542234.5; ticks every 200 m from 541400
  axes.origin_y_m = 5234000.0;
  axes.cell_size_x_m = axes.cell_size_y_m = 10.0;
  style.map_axes = axes;
  const nearshore::Image image = nearshore::render_heat_map(field, style);
  const nearshore::HeatMapPlacement placement = nearshore::heat_map_placement(100, 60, style);
  ASSERT_DOUBLE_EQ(placement.pixels_per_cell, 5.0);
  const int tick_row = static_cast<int>(placement.top_px) + placement.height_px + 3;  // inside the tick mark
  auto dark = [&](int x, int y) {
    const nearshore::Rgb c = image.get(x, y);
    return c[0] + c[1] + c[2] < 1.0f;
  };
  for (double easting = 541400.0; easting <= 542200.0; easting += 200.0) {
    const int px = static_cast<int>(std::lround(placement.left_px + (easting - axes.origin_x_m) / 10.0 * 5.0));
    EXPECT_TRUE(dark(px, tick_row) || dark(px - 1, tick_row) || dark(px + 1, tick_row)) << "tick at " << easting;
  }
  // Half-way between two ticks there is none.
  const int between = static_cast<int>(placement.left_px + (541500.0 - axes.origin_x_m) / 10.0 * 5.0);
  EXPECT_FALSE(dark(between, tick_row));
  EXPECT_GT(placement.legend_top_px, placement.top_px + placement.height_px + 20) << "room for the labels";
  EXPECT_LT(placement.legend_top_px, image.height());
}
