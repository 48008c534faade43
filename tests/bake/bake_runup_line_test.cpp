// The run-up line as lines (issue 19, runup_line.hpp): the front cells of small hand-drawn wet/dry
// maps chained along the shore with the never-wet ground on the left, whose answers are read off
// the picture, and the GeoJSON file (wave_statistics_geojson.cpp) read back with OGR. The maps go
// through the real WaveStatistics (one solver step's surface elevation), so the front is the one
// the bake writes into wave_statistics.tif, not a second definition of it.
#include <gdal_priv.h>
#include <ogr_spatialref.h>
#include <ogrsf_frmts.h>

#include <array>
#include <cmath>
#include <fstream>
#include <memory>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "bake_test_support.hpp"
#include "nearshore/bake/runup_line.hpp"
#include "nearshore/bake/wave_statistics.hpp"
#include "nearshore/core/error.hpp"

namespace nearshore::bake {
namespace {
namespace fs = std::filesystem;
using testing::scratch_folder;

constexpr double kDryDepth_m = 0.01;

// The highest water level a test gives a wet cell: distinct per cell, so that a vertex's z names its
// cell, and well above the dry threshold on ground 1 m deep.
float level_m(int column, int row) { return 0.1f + 0.01f * static_cast<float>(column) + 0.1f * static_cast<float>(row); }

// A map drawn as it is read: the first string is the NORTHERN row; '.' is ground the water reached
// (still-water depth 1 m), '#' ground it never reached (1 m above still water).
struct Drawn {
  GridGeometry geometry;
  WaveStatistics statistics;
};
Drawn drawn(const std::vector<std::string>& picture, double spacing_m = 2.0) {
  GridGeometry geometry;
  geometry.columns = static_cast<int>(picture.front().size());
  geometry.rows = static_cast<int>(picture.size());
  geometry.spacing_m = spacing_m;
  HarbourGrid harbour = HarbourGrid::open_water(geometry, 1.0f);
  Raster<float> eta(geometry.columns, geometry.rows);
  for (int row = 0; row < geometry.rows; ++row)
    for (int column = 0; column < geometry.columns; ++column) {
      const bool reached = picture[static_cast<std::size_t>(geometry.rows - 1 - row)][static_cast<std::size_t>(column)] == '.';
      if (!reached) {
        harbour.still_water_depth_m(column, row) = -1.0f;
        harbour.land(column, row) = kLandCell;
      }
      eta(column, row) = reached ? level_m(column, row) : 0.0f;
    }
  Drawn result{geometry, WaveStatistics(harbour, kDryDepth_m)};
  result.statistics.add_step(eta);
  return result;
}

std::vector<RunupLine> trace(const WaveStatistics& statistics) {
  return trace_runup_lines(statistics.runup_line_water_level_m(), statistics.maximum_surface_elevation_m());
}

using Cells = std::vector<std::pair<int, int>>;
Cells cells_of(const RunupLine& line) {
  Cells cells;
  for (const RunupVertex& vertex : line.vertices) cells.emplace_back(vertex.column, vertex.row);
  return cells;
}

// Every vertex carries its own cell's level: the band's value, nothing interpolated.
void expect_levels_of_their_cells(const RunupLine& line) {
  for (const RunupVertex& vertex : line.vertices) EXPECT_EQ(vertex.water_level_m, level_m(vertex.column, vertex.row));
}

TEST(RunupLine, StraightBeachIsOneLineWithOneVertexPerRowNorthToSouth) {
  const Drawn map = drawn({"....##",
                           "....##",
                           "....##",
                           "....##",
                           "....##"});
  const std::vector<RunupLine> lines = trace(map.statistics);
  ASSERT_EQ(lines.size(), 1u);
  const RunupLine& beach = lines.front();
  // Land to the east on the left: the line runs south, from the northern edge to the southern one.
  EXPECT_EQ(cells_of(beach), (Cells{{3, 4}, {3, 3}, {3, 2}, {3, 1}, {3, 0}}));
  EXPECT_FALSE(beach.closed);
  expect_levels_of_their_cells(beach);
  EXPECT_EQ(beach.highest_water_level_m(), level_m(3, 4));
  EXPECT_EQ(beach.lowest_water_level_m(), level_m(3, 0));
  EXPECT_EQ(beach.cell_count(), 5);
  EXPECT_DOUBLE_EQ(beach.length_m(map.geometry), 4 * 2.0);  // four steps of one 2 m cell
}

TEST(RunupLine, IslandIsAClosedRingAnticlockwise) {
  const Drawn map = drawn({"......",
                           "..##..",
                           "..##..",
                           "......",
                           "......"});
  const std::vector<RunupLine> lines = trace(map.statistics);
  ASSERT_EQ(lines.size(), 1u);
  const RunupLine& ring = lines.front();
  EXPECT_TRUE(ring.closed);
  // The eight cells beside the 2 x 2 island (not its diagonal corners, which touch it only at a
  // point), anticlockwise from the south-western one: land on the left all the way round.
  EXPECT_EQ(cells_of(ring), (Cells{{2, 1}, {3, 1}, {4, 2}, {4, 3}, {3, 4}, {2, 4}, {1, 3}, {1, 2}}));
  expect_levels_of_their_cells(ring);
  EXPECT_EQ(ring.cell_count(), 8);
  // Four straight steps along the sides and four diagonal ones round the corners, closing included.
  EXPECT_DOUBLE_EQ(ring.length_m(map.geometry), 4 * 2.0 + 4 * 2.0 * std::sqrt(2.0));
}

TEST(RunupLine, TwoBeachesAreTwoLines) {
  const Drawn map = drawn({"##....##",
                           "##....##",
                           "##....##"});
  const std::vector<RunupLine> lines = trace(map.statistics);
  ASSERT_EQ(lines.size(), 2u);
  // Land on the left: the western beach runs north, the eastern one south; the western comes first
  // (its first cell is met first scanning from the south-west).
  EXPECT_EQ(cells_of(lines[0]), (Cells{{2, 0}, {2, 1}, {2, 2}}));
  EXPECT_EQ(cells_of(lines[1]), (Cells{{5, 2}, {5, 1}, {5, 0}}));
  for (const RunupLine& line : lines) {
    EXPECT_FALSE(line.closed);
    expect_levels_of_their_cells(line);
  }
}

TEST(RunupLine, SingleCellIsALineOfOneVertexAndNoLength) {
  // A pool the water filled in one cell: a ring of one cell. A front cell at the grid's edge: an open
  // line of one cell (the edge is no shore).
  const Drawn pool = drawn({"###",
                            "#.#",
                            "###"});
  std::vector<RunupLine> lines = trace(pool.statistics);
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_EQ(cells_of(lines[0]), (Cells{{1, 1}}));
  EXPECT_TRUE(lines[0].closed);
  EXPECT_EQ(lines[0].length_m(pool.geometry), 0.0);
  EXPECT_EQ(lines[0].highest_water_level_m(), level_m(1, 1));

  const Drawn edge = drawn({".##"});
  lines = trace(edge.statistics);
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_EQ(cells_of(lines[0]), (Cells{{0, 0}}));
  EXPECT_FALSE(lines[0].closed);
  EXPECT_EQ(lines[0].cell_count(), 1);
}

TEST(RunupLine, CreekIsFollowedUpOneBankAndDownTheOther) {
  const Drawn map = drawn({"#######",
                           "###.###",
                           "###.###",
                           "......."});
  const std::vector<RunupLine> lines = trace(map.statistics);
  ASSERT_EQ(lines.size(), 1u);
  // Eastward along the coast (land to the north), up the creek's west bank, round its head, down its
  // east bank and on east: the shore as walked, the creek's two cells twice.
  EXPECT_EQ(cells_of(lines[0]), (Cells{{0, 0}, {1, 0}, {2, 0}, {3, 1}, {3, 2}, {3, 1}, {4, 0}, {5, 0}, {6, 0}}));
  EXPECT_EQ(lines[0].cell_count(), 8);  // (3, 0) has water on all four sides: no front
}

TEST(RunupLine, WetCellsTouchingAtACornerAreJoinedThroughIt) {
  // A diagonal creek: the water reached three cells that touch only at their corners. Each bank is
  // one line through the three (the water passes the corners, the land meets across them).
  const Drawn map = drawn({"##.",
                           "#.#",
                           ".##"});
  const std::vector<RunupLine> lines = trace(map.statistics);
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(cells_of(lines[0]), (Cells{{0, 0}, {1, 1}, {2, 2}}));  // the north-western bank, land on the left
  EXPECT_EQ(cells_of(lines[1]), (Cells{{2, 2}, {1, 1}, {0, 0}}));  // the south-eastern bank
}

// Any map: the lines hold exactly the band's cells; consecutive vertices (and a ring's last and
// first) are 8-neighbours; each vertex has a never-wet 4-neighbour. 200 random 9 x 7 maps with a
// fixed seed (deterministic), half of the cells never wet: every corner case of two cells meeting.
TEST(RunupLine, EveryFrontCellOfRandomMapsIsOnAConnectedLine) {
  std::mt19937 random(20261124);
  std::bernoulli_distribution reached(0.5);
  for (int map_index = 0; map_index < 200; ++map_index) {
    std::vector<std::string> picture(7, std::string(9, '.'));
    for (std::string& line : picture)
      for (char& cell : line) cell = reached(random) ? '.' : '#';
    const Drawn map = drawn(picture, 1.0);
    const Raster<float> front = map.statistics.runup_line_water_level_m();
    const Raster<float> envelope = map.statistics.maximum_surface_elevation_m();
    const std::vector<RunupLine> lines = trace_runup_lines(front, envelope);
    std::set<std::pair<int, int>> band_cells, line_cells;
    for (int row = 0; row < front.rows(); ++row)
      for (int column = 0; column < front.columns(); ++column)
        if (!std::isnan(front(column, row))) band_cells.emplace(column, row);
    const auto never_wet = [&](int column, int row) {
      return column >= 0 && column < envelope.columns() && row >= 0 && row < envelope.rows() && std::isnan(envelope(column, row));
    };
    const auto neighbours = [](const RunupVertex& a, const RunupVertex& b) {
      return std::abs(a.column - b.column) <= 1 && std::abs(a.row - b.row) <= 1 && !(a.column == b.column && a.row == b.row);
    };
    for (const RunupLine& line : lines) {
      ASSERT_FALSE(line.vertices.empty());
      for (std::size_t k = 0; k < line.vertices.size(); ++k) {
        const RunupVertex& vertex = line.vertices[k];
        line_cells.emplace(vertex.column, vertex.row);
        EXPECT_EQ(vertex.water_level_m, front(vertex.column, vertex.row));
        EXPECT_TRUE(never_wet(vertex.column + 1, vertex.row) || never_wet(vertex.column - 1, vertex.row) ||
                    never_wet(vertex.column, vertex.row + 1) || never_wet(vertex.column, vertex.row - 1));
        if (k > 0) {
          EXPECT_TRUE(neighbours(line.vertices[k - 1], vertex)) << "map " << map_index;
        }
      }
      if (line.closed && line.vertices.size() > 1) {
        EXPECT_TRUE(neighbours(line.vertices.back(), line.vertices.front())) << "map " << map_index;
      }
    }
    EXPECT_EQ(line_cells, band_cells) << "map " << map_index;
  }
}

TEST(RunupLine, RastersOfDifferentStatisticsAreRefused) {
  const Drawn beach = drawn({"..#", "..#"}), other = drawn({".##", ".##"}), small = drawn({"..#"});
  // A front cell the envelope does not put on the front, and rasters of two sizes.
  EXPECT_THROW(trace_runup_lines(beach.statistics.runup_line_water_level_m(), other.statistics.maximum_surface_elevation_m()),
               Error);
  EXPECT_THROW(trace_runup_lines(beach.statistics.runup_line_water_level_m(), small.statistics.maximum_surface_elevation_m()),
               Error);
}

// ---- the GeoJSON file --------------------------------------------------------------------------------

struct ReadFeature {
  std::vector<std::array<double, 3>> points;
  double water_level_max_m, water_level_min_m, length_m;
  int cells;
  bool closed;
};
struct ReadFile {
  std::vector<ReadFeature> features;
  bool has_crs = false;
  std::string crs_authority_code;
  OGRwkbGeometryType geometry_type = wkbUnknown;
};
ReadFile read_with_ogr(const fs::path& file) {
  GDALAllRegister();
  ReadFile result;
  GDALDatasetUniquePtr dataset(GDALDataset::Open(file.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
  EXPECT_NE(dataset, nullptr) << file;
  if (!dataset) return result;
  EXPECT_EQ(dataset->GetLayerCount(), 1);
  OGRLayer* layer = dataset->GetLayer(0);
  result.geometry_type = layer->GetGeomType();
  if (const OGRSpatialReference* crs = layer->GetSpatialRef()) {
    result.has_crs = true;
    if (crs->GetAuthorityCode(nullptr)) result.crs_authority_code = std::string(crs->GetAuthorityName(nullptr)) + ":" + crs->GetAuthorityCode(nullptr);
  }
  for (const auto& feature : *layer) {
    ReadFeature read;
    const OGRGeometry* geometry = feature->GetGeometryRef();
    EXPECT_EQ(wkbFlatten(geometry->getGeometryType()), wkbLineString);
    for (const OGRPoint& point : *geometry->toLineString()) read.points.push_back({point.getX(), point.getY(), point.getZ()});
    read.water_level_max_m = feature->GetFieldAsDouble("water_level_max_m");
    read.water_level_min_m = feature->GetFieldAsDouble("water_level_min_m");
    read.length_m = feature->GetFieldAsDouble("length_m");
    read.cells = feature->GetFieldAsInteger("cells");
    read.closed = feature->GetFieldAsInteger("closed") != 0;
    result.features.push_back(std::move(read));
  }
  return result;
}

// A beach and an island on a UTM grid: the file read back with OGR has one feature per traced line,
// the vertices at the cells' centres in the grid's CRS with z = the band's level, the properties of
// the line, the ring closed by repeating its first position.
TEST(RunupLineFile, LinesReadBackWithOgrInTheGridsCrs) {
  const fs::path folder = scratch_folder();
  Drawn map = drawn({"........##",
                     "..##....##",
                     "..##....##",
                     "........##"},
                    5.0);
  OGRSpatialReference utm;
  utm.importFromEPSG(32610);
  char* wkt = nullptr;
  utm.exportToWkt(&wkt);
  map.geometry.crs_wkt = wkt;
  CPLFree(wkt);
  map.geometry.origin_x_m = 540000.0;
  map.geometry.origin_y_m = 5230000.0;
  write_runup_line_geojson(folder / "runup.geojson", map.statistics, map.geometry, 10.0, 70.0);

  const std::vector<RunupLine> lines = trace(map.statistics);
  const ReadFile file = read_with_ogr(folder / "runup.geojson");
  EXPECT_EQ(wkbFlatten(file.geometry_type), wkbLineString);
  EXPECT_TRUE(OGR_GT_HasZ(file.geometry_type));
  EXPECT_EQ(file.crs_authority_code, "EPSG:32610");
  ASSERT_EQ(file.features.size(), lines.size());
  ASSERT_EQ(lines.size(), 2u);  // the beach (open) and the island (a ring)
  for (std::size_t f = 0; f < lines.size(); ++f) {
    const RunupLine& line = lines[f];
    const ReadFeature& feature = file.features[f];
    ASSERT_EQ(feature.points.size(), line.vertices.size() + (line.closed ? 1 : 0));
    for (std::size_t k = 0; k < feature.points.size(); ++k) {
      const RunupVertex& vertex = line.vertices[k % line.vertices.size()];
      // 15 significant figures: 1e-8 m at 5e6 m; z is a float written as a double, read back exactly.
      EXPECT_NEAR(feature.points[k][0], 540000.0 + (vertex.column + 0.5) * 5.0, 1e-6);
      EXPECT_NEAR(feature.points[k][1], 5230000.0 + (vertex.row + 0.5) * 5.0, 1e-6);
      EXPECT_EQ(static_cast<float>(feature.points[k][2]), vertex.water_level_m);
    }
    EXPECT_EQ(static_cast<float>(feature.water_level_max_m), line.highest_water_level_m());
    EXPECT_EQ(static_cast<float>(feature.water_level_min_m), line.lowest_water_level_m());
    EXPECT_EQ(feature.cells, line.cell_count());
    EXPECT_NEAR(feature.length_m, line.length_m(map.geometry), 1e-9);
    EXPECT_EQ(feature.closed, line.closed);
  }
  EXPECT_FALSE(file.features[0].closed);
  EXPECT_TRUE(file.features[1].closed);
  EXPECT_EQ(file.features[1].points.front(), file.features[1].points.back());
}

// A laboratory grid in local metres: no CRS in the layer, and the description says so; a front of
// one cell is a LineString of its position twice (a LineString has two or more positions, RFC 7946).
TEST(RunupLineFile, LocalMetresHaveNoCrsAndOneCellIsTwoPositions) {
  const fs::path folder = scratch_folder();
  const Drawn pool = drawn({"###",
                            "#.#",
                            "###"});
  write_runup_line_geojson(folder / "runup.geojson", pool.statistics, pool.geometry, 0.0, 1.0);
  const ReadFile file = read_with_ogr(folder / "runup.geojson");
  ASSERT_EQ(file.features.size(), 1u);
  ASSERT_EQ(file.features[0].points.size(), 2u);
  EXPECT_EQ(file.features[0].points[0], file.features[0].points[1]);
  EXPECT_EQ(file.features[0].points[0][0], 3.0);  // cell (1, 1) of 2 m cells from the origin
  EXPECT_EQ(file.features[0].cells, 1);
  EXPECT_EQ(file.features[0].length_m, 0.0);
  const nlohmann::json text = nlohmann::json::parse(std::ifstream(folder / "runup.geojson"));
  EXPECT_EQ(text.value("type", ""), "FeatureCollection");
  EXPECT_FALSE(text.contains("crs"));
  EXPECT_NE(text.value("description", "").find("local metres"), std::string::npos) << text.dump();
}

// A harbour grid in a transverse Mercator of its own (`nearshore bathy`'s local-tm) has no EPSG code
// for GeoJSON's "crs" member: the line is written in RFC 7946 longitude and latitude, which map back
// onto the cell centres (within the 9 decimals' 0.1 mm) and keep z.
TEST(RunupLineFile, CrsWithoutAnEpsgCodeIsWrittenAsLongitudeAndLatitude) {
  const fs::path folder = scratch_folder();
  Drawn map = drawn({"....##",
                     "....##"},
                    10.0);
  OGRSpatialReference local_tm;  // as bathymetry/src/projection.cpp makes it
  local_tm.SetWellKnownGeogCS("WGS84");
  local_tm.SetTM(47.28, -122.45, 1.0, 0.0, 0.0);
  local_tm.SetProjCS("nearshore local transverse Mercator");
  char* wkt = nullptr;
  local_tm.exportToWkt(&wkt);
  map.geometry.crs_wkt = wkt;
  CPLFree(wkt);
  map.geometry.origin_x_m = -300.0;
  map.geometry.origin_y_m = 200.0;
  write_runup_line_geojson(folder / "runup.geojson", map.statistics, map.geometry, 0.0, 1.0);
  const nlohmann::json text = nlohmann::json::parse(std::ifstream(folder / "runup.geojson"));
  EXPECT_FALSE(text.contains("crs"));
  EXPECT_NE(text.value("description", "").find("longitude and latitude"), std::string::npos) << text.dump();

  const ReadFile file = read_with_ogr(folder / "runup.geojson");
  const std::vector<RunupLine> lines = trace(map.statistics);
  ASSERT_EQ(lines.size(), 1u);
  ASSERT_EQ(file.features.size(), 1u);
  OGRSpatialReference wgs84;
  wgs84.importFromEPSG(4326);
  wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  local_tm.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  const std::unique_ptr<OGRCoordinateTransformation> to_grid(OGRCreateCoordinateTransformation(&wgs84, &local_tm));
  ASSERT_NE(to_grid, nullptr);
  ASSERT_EQ(file.features[0].points.size(), lines[0].vertices.size());
  for (std::size_t k = 0; k < lines[0].vertices.size(); ++k) {
    const RunupVertex& vertex = lines[0].vertices[k];
    double x = file.features[0].points[k][0], y = file.features[0].points[k][1];
    EXPECT_NEAR(x, -122.45, 0.01);  // degrees near the projection's centre, not metres
    EXPECT_NEAR(y, 47.28, 0.01);
    ASSERT_TRUE(to_grid->Transform(1, &x, &y));
    EXPECT_NEAR(x, map.geometry.cell_centre_x_m(vertex.column), 1e-3);
    EXPECT_NEAR(y, map.geometry.cell_centre_y_m(vertex.row), 1e-3);
    // 9 decimals of a metre, and GDAL's number formatting rounds a run of nines (0.1299999952 is
    // written 0.13): 5e-9 m at most, far below any water level a solver resolves.
    EXPECT_NEAR(file.features[0].points[k][2], vertex.water_level_m, 1e-8);
  }
  EXPECT_DOUBLE_EQ(file.features[0].length_m, 10.0);  // in the grid's metres, not degrees
}

}  // namespace
}  // namespace nearshore::bake
