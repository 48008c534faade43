#include "nearshore/core/harbour_grid.hpp"

#include <fstream>
#include <string_view>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>

#include <cmath>
#include <limits>

#include <fmt/core.h>

#include "nearshore/core/atomic_file.hpp"
#include "nearshore/core/error.hpp"

namespace nearshore {
namespace fs = std::filesystem;
namespace {

constexpr const char* kGeometryAttribute = "nearshore_geometry";
constexpr const char* kStructuresAttribute = "nearshore_structures";
constexpr const char* kFormatAttribute = "nearshore_format";
constexpr const char* kFormatName = "nearshore harbour grid 1";
// The optional channel (harbour_grid.hpp): grids without it read as before.
constexpr const char* kStoneDiameterChannel = "stone_diameter";

// EXR line 0 is north; Raster row 0 is south. One flip, here, in both directions.
std::vector<float> to_exr_lines(const Raster<float>& raster) {
  std::vector<float> lines(raster.size());
  for (int row = 0; row < raster.rows(); ++row)
    std::copy_n(&raster(0, row), raster.columns(),
                &lines[static_cast<std::size_t>(raster.rows() - 1 - row) * raster.columns()]);
  return lines;
}

Raster<float> from_exr_lines(const std::vector<float>& lines, int columns, int rows) {
  Raster<float> raster(columns, rows);
  for (int row = 0; row < rows; ++row)
    std::copy_n(&lines[static_cast<std::size_t>(rows - 1 - row) * columns], columns, &raster(0, row));
  return raster;
}

}  // namespace

HarbourGrid HarbourGrid::open_water(const GridGeometry& geometry, float depth_m) {
  HarbourGrid grid;
  grid.geometry = geometry;
  grid.still_water_depth_m = Raster<float>(geometry.columns, geometry.rows, depth_m);
  grid.land = Raster<std::uint8_t>(geometry.columns, geometry.rows, 0);
  grid.porosity = Raster<float>(geometry.columns, geometry.rows, 1.0f);
  grid.coast_distance_m = Raster<float>(geometry.columns, geometry.rows, std::numeric_limits<float>::infinity());
  return grid;
}

void write_harbour_grid(const fs::path& depth_exr, const HarbourGrid& grid) {
  const int columns = grid.geometry.columns, rows = grid.geometry.rows;
  Raster<float> land(columns, rows);
  for (std::size_t i = 0; i < land.size(); ++i)
    land.values()[i] = grid.land.values()[i] == kOutsideChartCell ? 2.f : grid.land.values()[i] ? 1.f : 0.f;
  std::vector<std::pair<const char*, const Raster<float>*>> channels = {{"depth", &grid.still_water_depth_m},
                                                                       {"land", &land},
                                                                       {"porosity", &grid.porosity},
                                                                       {"coast_distance", &grid.coast_distance_m}};
  if (grid.porous_stone_diameter_m.size() > 0) channels.emplace_back(kStoneDiameterChannel, &grid.porous_stone_diameter_m);
  for (const auto& [name, raster] : channels)
    if (raster->columns() != columns || raster->rows() != rows)
      throw Error(depth_exr.string(), fmt::format("channel {} is {} x {} but the grid is {} x {}", name,
                                                  raster->columns(), raster->rows(), columns, rows));
  std::vector<std::vector<float>> lines;
  for (const auto& [name, raster] : channels) lines.push_back(to_exr_lines(*raster));
  write_file_atomically(depth_exr, [&](const fs::path& temporary) {
    try {
      Imf::Header header(columns, rows);
      header.compression() = Imf::ZIP_COMPRESSION;
      header.insert(kFormatAttribute, Imf::StringAttribute(kFormatName));
      header.insert(kGeometryAttribute, Imf::StringAttribute(nlohmann::json(grid.geometry).dump()));
      if (!grid.structures.empty())
        header.insert(kStructuresAttribute, Imf::StringAttribute(nlohmann::json(grid.structures).dump()));
      Imf::FrameBuffer frame_buffer;
      for (std::size_t c = 0; c < channels.size(); ++c) {
        header.channels().insert(channels[c].first, Imf::Channel(Imf::FLOAT));
        frame_buffer.insert(channels[c].first,
                            Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(lines[c].data()), sizeof(float),
                                       sizeof(float) * columns));
      }
      Imf::OutputFile file(temporary.c_str(), header);
      file.setFrameBuffer(frame_buffer);
      file.writePixels(rows);
    } catch (const std::exception& e) {
      throw Error(depth_exr.string(), std::string("writing the harbour grid failed: ") + e.what(),
                  "free disk space or choose another output folder");
    }
  });
}

HarbourGrid read_harbour_grid(const fs::path& depth_exr) {
  require_readable_file(depth_exr, "a harbour grid written by `nearshore bathy` (depth.exr)");
  // What the file is when it is no EXR (its first bytes), so that a valid GeoTIFF or a picture is
  // not called "truncated or corrupt" (issue 44): it is simply not the file a bake reads.
  {
    char magic[8] = {};
    std::ifstream in(depth_exr, std::ios::binary);
    in.read(magic, sizeof magic);
    const std::string_view head(magic, static_cast<std::size_t>(in.gcount()));
    const char* kind = nullptr;
    if (head.starts_with(std::string_view("II*\0", 4)) || head.starts_with(std::string_view("MM\0*", 4)) ||
        head.starts_with(std::string_view("II+\0", 4)) || head.starts_with(std::string_view("MM\0+", 4)))
      kind = "a TIFF (a GeoTIFF such as depth.tif)";
    else if (head.starts_with("\x89PNG"))
      kind = "a PNG picture";
    else if (head.starts_with("\x89HDF") || head.starts_with("CDF"))
      kind = "a NetCDF or HDF5 file";
    if (kind)
      throw Error(depth_exr.string(),
                  fmt::format("is {}, not a harbour grid: a bake reads the OpenEXR depth.exr that `nearshore bathy` writes "
                              "(depth, land, porosity, coastline distance and the georeference)",
                              kind),
                  "pass the depth.exr beside it, or make one from this raster with `nearshore bathy FILE -o DIR` and pass "
                  "DIR/depth.exr");
  }
  HarbourGrid grid;
  try {
    Imf::InputFile file(depth_exr.c_str());
    const Imf::Header& header = file.header();
    const auto* geometry = header.findTypedAttribute<Imf::StringAttribute>(kGeometryAttribute);
    if (!geometry)
      throw Error(depth_exr.string(), "is an EXR file but not a nearshore harbour grid (no georeference)",
                  "make it with `nearshore bathy ... -o DIR` and pass DIR/depth.exr");
    grid.geometry = nlohmann::json::parse(geometry->value()).get<GridGeometry>();
    if (const auto* structures = header.findTypedAttribute<Imf::StringAttribute>(kStructuresAttribute))
      grid.structures = nlohmann::json::parse(structures->value()).get<std::vector<CoastalStructure>>();
    const Imath::Box2i window = header.dataWindow();
    const int columns = window.max.x - window.min.x + 1, rows = window.max.y - window.min.y + 1;
    if (columns != grid.geometry.columns || rows != grid.geometry.rows)
      throw Error(depth_exr.string(), fmt::format("image is {} x {} but its georeference says {} x {}", columns,
                                                  rows, grid.geometry.columns, grid.geometry.rows),
                  "rewrite it with `nearshore bathy`");
    const char* names[] = {"depth", "land", "porosity", "coast_distance"};
    std::vector<std::vector<float>> lines(4, std::vector<float>(static_cast<std::size_t>(columns) * rows));
    Imf::FrameBuffer frame_buffer;
    for (int c = 0; c < 4; ++c) {
      if (!header.channels().findChannel(names[c]))
        throw Error(depth_exr.string(), fmt::format("has no '{}' channel", names[c]),
                    "rewrite it with `nearshore bathy`");
      char* base = reinterpret_cast<char*>(lines[c].data()) -
                   (static_cast<std::ptrdiff_t>(window.min.y) * columns + window.min.x) * sizeof(float);
      frame_buffer.insert(names[c], Imf::Slice(Imf::FLOAT, base, sizeof(float), sizeof(float) * columns));
    }
    const bool has_stone_diameter = header.channels().findChannel(kStoneDiameterChannel) != nullptr;
    if (has_stone_diameter) {
      lines.emplace_back(static_cast<std::size_t>(columns) * rows);
      char* base = reinterpret_cast<char*>(lines.back().data()) -
                   (static_cast<std::ptrdiff_t>(window.min.y) * columns + window.min.x) * sizeof(float);
      frame_buffer.insert(kStoneDiameterChannel, Imf::Slice(Imf::FLOAT, base, sizeof(float), sizeof(float) * columns));
    }
    file.setFrameBuffer(frame_buffer);
    file.readPixels(window.min.y, window.max.y);
    if (has_stone_diameter) grid.porous_stone_diameter_m = from_exr_lines(lines[4], columns, rows);
    grid.still_water_depth_m = from_exr_lines(lines[0], columns, rows);
    const Raster<float> land = from_exr_lines(lines[1], columns, rows);
    grid.land = Raster<std::uint8_t>(columns, rows);
    for (std::size_t i = 0; i < land.size(); ++i)
      grid.land.values()[i] = land.values()[i] > 1.5f ? kOutsideChartCell : land.values()[i] > 0.5f ? kLandCell : kWaterCell;
    grid.porosity = from_exr_lines(lines[2], columns, rows);
    grid.coast_distance_m = from_exr_lines(lines[3], columns, rows);
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw Error(depth_exr.string(), std::string("cannot be read as a harbour grid: ") + e.what(),
                "if it is the depth.exr of `nearshore bathy`, it is truncated or corrupt: regenerate it with `nearshore bathy`");
  }
  for (std::size_t i = 0; i < grid.porous_stone_diameter_m.size(); ++i)
    if (!(grid.porous_stone_diameter_m.values()[i] > 0.0f) || !std::isfinite(grid.porous_stone_diameter_m.values()[i])) {
      const int column = static_cast<int>(i % grid.geometry.columns), row = static_cast<int>(i / grid.geometry.columns);
      throw Error(depth_exr.string(),
                  fmt::format("stone diameter {} m at cell ({}, {}) is not a positive number", grid.porous_stone_diameter_m.values()[i],
                              column, row),
                  "rewrite it with `nearshore bathy` (the channel is optional: without it every cell takes the solver's stone diameter)");
    }
  for (int row = 0; row < grid.geometry.rows; ++row)
    for (int column = 0; column < grid.geometry.columns; ++column)
      if (!std::isfinite(grid.still_water_depth_m(column, row)))
        throw Error(depth_exr.string(),
                    fmt::format("depth is NaN at cell ({}, {}) (x={:.1f} m, y={:.1f} m)", column, row,
                                grid.geometry.cell_centre_x_m(column), grid.geometry.cell_centre_y_m(row)),
                    "fill it when gridding (`nearshore bathy`) or mark it as land");
  return grid;
}

}  // namespace nearshore
