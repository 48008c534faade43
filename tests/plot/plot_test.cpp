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
