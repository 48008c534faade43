#include "nearshore/core/harbour_grid.hpp"

#include <fstream>
#include <string_view>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfInputPart.h>
#include <OpenEXR/ImfMultiPartInputFile.h>
#include <OpenEXR/ImfMultiPartOutputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfOutputPart.h>
#include <OpenEXR/ImfPartType.h>
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
// The optional second part (harbour_grid.hpp): the surroundings, one channel.
constexpr const char* kGridPartName = "harbour_grid";
constexpr const char* kSurroundingsPartName = "surroundings";
constexpr const char* kSurroundingsDepthChannel = "depth";

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

// The surroundings' part (harbour_grid.hpp), validated against the grid it surrounds.
Surroundings read_surroundings_part(const fs::path& depth_exr, Imf::MultiPartInputFile& multi_part, int index,
                                    const GridGeometry& grid) {
  Imf::InputPart part(multi_part, index);
  const Imf::Header& header = part.header();
  const std::string where = fmt::format("{} (part {}, \"{}\")", depth_exr.string(), index, kSurroundingsPartName);
  const auto* geometry = header.findTypedAttribute<Imf::StringAttribute>(kGeometryAttribute);
  if (!geometry || !header.channels().findChannel(kSurroundingsDepthChannel))
    throw Error(where, fmt::format("has no {} attribute or no '{}' channel", kGeometryAttribute, kSurroundingsDepthChannel),
                "rewrite it with `nearshore bathy`");
  Surroundings surroundings;
  surroundings.geometry = nlohmann::json::parse(geometry->value()).get<GridGeometry>();
  const GridGeometry& g = surroundings.geometry;
  const Imath::Box2i window = header.dataWindow();
  const int columns = window.max.x - window.min.x + 1, rows = window.max.y - window.min.y + 1;
  if (columns != g.columns || rows != g.rows || columns < 2 || rows < 2)
    throw Error(where, fmt::format("image is {} x {} but its georeference says {} x {} (at least 2 x 2)", columns, rows,
                                   g.columns, g.rows),
                "rewrite it with `nearshore bathy`");
  if (!(g.spacing_x_m() > 0) || !(g.spacing_y_m() > 0) || g.crs_wkt != grid.crs_wkt || g.projection != grid.projection)
    throw Error(where, "is not in the harbour grid's projection, or its cells have no positive size",
                "rewrite it with `nearshore bathy` (the surroundings are gridded in the grid's own projection)");
  // Round the grid: `nearshore bathy` grids them over a box holding the grid's, but a bake that
  // resamples the grid may round its box out by half a cell; surroundings that do not even overlap
  // the grid are another place's.
  if (g.origin_x_m >= grid.origin_x_m + grid.width_m() || g.origin_x_m + g.width_m() <= grid.origin_x_m ||
      g.origin_y_m >= grid.origin_y_m + grid.height_m() || g.origin_y_m + g.height_m() <= grid.origin_y_m)
    throw Error(where, fmt::format("x {:.1f}..{:.1f} m, y {:.1f}..{:.1f} m do not overlap the grid's x {:.1f}..{:.1f} m, y {:.1f}..{:.1f} m",
                                   g.origin_x_m, g.origin_x_m + g.width_m(), g.origin_y_m, g.origin_y_m + g.height_m(),
                                   grid.origin_x_m, grid.origin_x_m + grid.width_m(), grid.origin_y_m,
                                   grid.origin_y_m + grid.height_m()),
                "rewrite it with `nearshore bathy`");
  std::vector<float> lines(static_cast<std::size_t>(columns) * rows);
  Imf::FrameBuffer frame_buffer;
  char* base = reinterpret_cast<char*>(lines.data()) -
               (static_cast<std::ptrdiff_t>(window.min.y) * columns + window.min.x) * sizeof(float);
  frame_buffer.insert(kSurroundingsDepthChannel, Imf::Slice(Imf::FLOAT, base, sizeof(float), sizeof(float) * columns));
  part.setFrameBuffer(frame_buffer);
  part.readPixels(window.min.y, window.max.y);
  surroundings.still_water_depth_m = from_exr_lines(lines, columns, rows);
  for (int row = 0; row < rows; ++row)
    for (int column = 0; column < columns; ++column)
      if (std::isinf(surroundings.still_water_depth_m(column, row)))
        throw Error(where, fmt::format("depth is infinite at cell ({}, {}) (x={:.1f} m, y={:.1f} m)", column, row,
                                       g.cell_centre_x_m(column), g.cell_centre_y_m(row)),
                    "rewrite it with `nearshore bathy` (NaN marks no data; every other value is a depth in metres)");
  return surroundings;
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
  const Surroundings& surroundings = grid.surroundings;
  if (!surroundings.empty() && (surroundings.still_water_depth_m.columns() != surroundings.geometry.columns ||
                                surroundings.still_water_depth_m.rows() != surroundings.geometry.rows))
    throw Error(depth_exr.string(), fmt::format("the surroundings' depth is {} x {} but their geometry says {} x {}",
                                                surroundings.still_water_depth_m.columns(), surroundings.still_water_depth_m.rows(),
                                                surroundings.geometry.columns, surroundings.geometry.rows));
  const std::vector<float> surroundings_lines = surroundings.empty() ? std::vector<float>{} : to_exr_lines(surroundings.still_water_depth_m);
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
      if (surroundings.empty()) {  // one part, byte for byte the file written before the surroundings
        Imf::OutputFile file(temporary.c_str(), header);
        file.setFrameBuffer(frame_buffer);
        file.writePixels(rows);
        return;
      }
      const int outer_columns = surroundings.geometry.columns, outer_rows = surroundings.geometry.rows;
      // The parts of one file share their display window (OpenEXR's rule); each has its data window.
      Imf::Header outer(header.displayWindow(), Imath::Box2i({0, 0}, {outer_columns - 1, outer_rows - 1}));
      outer.compression() = Imf::ZIP_COMPRESSION;
      outer.insert(kFormatAttribute, Imf::StringAttribute(kFormatName));
      outer.insert(kGeometryAttribute, Imf::StringAttribute(nlohmann::json(surroundings.geometry).dump()));
      outer.channels().insert(kSurroundingsDepthChannel, Imf::Channel(Imf::FLOAT));
      header.setName(kGridPartName);
      header.setType(Imf::SCANLINEIMAGE);
      outer.setName(kSurroundingsPartName);
      outer.setType(Imf::SCANLINEIMAGE);
      const Imf::Header headers[2] = {header, outer};
      Imf::MultiPartOutputFile file(temporary.c_str(), headers, 2);
      Imf::OutputPart grid_part(file, 0);
      grid_part.setFrameBuffer(frame_buffer);
      grid_part.writePixels(rows);
      Imf::FrameBuffer outer_buffer;
      outer_buffer.insert(kSurroundingsDepthChannel,
                          Imf::Slice(Imf::FLOAT, const_cast<char*>(reinterpret_cast<const char*>(surroundings_lines.data())),
                                     sizeof(float), sizeof(float) * outer_columns));
      Imf::OutputPart outer_part(file, 1);
      outer_part.setFrameBuffer(outer_buffer);
      outer_part.writePixels(outer_rows);
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
    Imf::MultiPartInputFile multi_part(depth_exr.c_str());
    Imf::InputPart file(multi_part, 0);
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
    for (int part = 1; part < multi_part.parts(); ++part)
      if (multi_part.header(part).hasName() && multi_part.header(part).name() == kSurroundingsPartName)
        grid.surroundings = read_surroundings_part(depth_exr, multi_part, part, grid.geometry);
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
