// build_site_terrain on the CPU: the ground follows the bilinear depth, the skirt continues the
// edge's land to its end and deepens the edge's water to the open sea, structures stand at their crest, and the dry mask
// covers their outline at still water and nothing far from it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "nearshore/playback/site_terrain.hpp"
#include "surroundings_fixture.hpp"

namespace nearshore {
namespace {
using playback::TerrainMesh;

constexpr double kOriginX = 500000.0, kOriginY = 5200000.0;

// 40 x 30 cells of 5 m: 6 m deep in the south rising to land 3 m up along the north edge.
HarbourGrid sloping_harbour() {
  GridGeometry g;
  g.columns = 40;
  g.rows = 30;
  g.spacing_m = 5.0;
  g.origin_x_m = kOriginX;
  g.origin_y_m = kOriginY;
  HarbourGrid h = HarbourGrid::open_water(g, 6.f);
  for (int j = 0; j < g.rows; ++j)
    for (int i = 0; i < g.columns; ++i) {
      const double y = (j + 0.5) * 5.0;
      h.still_water_depth_m(i, j) = float(std::clamp(0.1 * (110.0 - y), -3.0, 6.0));
      h.land(i, j) = h.still_water_depth_m(i, j) < 0 ? kLandCell : kWaterCell;
      h.coast_distance_m(i, j) = float(110.0 - y);
    }
  return h;
}

struct Vertex {
  double x, y, z, inland;
  int material;
};
Vertex vertex(const TerrainMesh& mesh, std::size_t k) {
  const float* v = &mesh.vertices[k * TerrainMesh::kFloatsPerVertex];
  return {v[0], v[1], v[2], v[3], int(std::lround(v[4]))};
}

}  // namespace

TEST(SiteTerrain, TheGroundIsTheBilinearDepthAndItsSkirtContinuesTheLandAndTheSea) {
  const HarbourGrid h = sloping_harbour();
  playback::TerrainOptions options;
  options.open_sea_depth_m = 20.0;
  const TerrainMesh mesh = playback::build_site_terrain(h, options);
  ASSERT_GT(mesh.ground_vertex_count, 0u);
  EXPECT_EQ(mesh.skirt_width_m, playback::kDefaultSkirtWidthM);  // max(100 km, the 200 m site)
  const double skirt = mesh.skirt_width_m;
  EXPECT_EQ(mesh.indices.size() % 3, 0u);
  int inside = 0, at_centres = 0, beyond_north = 0, far_out = 0;
  for (std::size_t k = 0; k < mesh.ground_vertex_count; ++k) {
    const Vertex v = vertex(mesh, k);
    EXPECT_EQ(v.material, 0);
    if (v.x >= 0 && v.x <= 200 && v.y >= 0 && v.y <= 150) {
      ++inside;
      EXPECT_NEAR(v.z, playback::ground_elevation_m(h, v.x, v.y), 1e-5);
      const double u = v.x / 5.0 - 0.5, w = v.y / 5.0 - 0.5;
      if (std::abs(u - std::round(u)) < 1e-6 && std::abs(w - std::round(w)) < 1e-6 && u >= 0 && w >= 0 && u < 40 && w < 30) {
        ++at_centres;  // a cell centre: exactly minus the cell's depth
        EXPECT_NEAR(v.z, -h.still_water_depth_m(int(std::lround(u)), int(std::lround(w))), 1e-5);
      }
    } else {
      // every skirt vertex is its twin's ground (what the water shader tests it against)
      EXPECT_NEAR(v.z, playback::skirt_ground_m(h, playback::SurroundingGround{}, 20.0, v.x, v.y), 1e-3 + 1e-6 * std::abs(v.z)) << "(" << v.x << ", " << v.y << ")";
      if (v.x >= 40 && v.x <= 160 && v.y > 150) {
        ++beyond_north;  // the land beyond the north edge (clear of its ends) stands at the edge's 3 m, to the end
        EXPECT_NEAR(v.z, 3.0, 1e-4) << "(" << v.x << ", " << v.y << ")";
        EXPECT_GT(v.inland, 35.0);
      } else if (v.x >= 40 && v.x <= 160 && v.y <= -skirt + 1e-6) {
        ++far_out;  // the skirt's outer ring beyond the south (water) edge is under the open sea
        EXPECT_NEAR(v.z, -20.0, 1e-4) << "(" << v.x << ", " << v.y << ")";
      }
    }
  }
  EXPECT_GT(inside, 79 * 59);  // two vertices a cell each way
  EXPECT_EQ(at_centres, 40 * 30);
  EXPECT_GT(beyond_north, 100);
  EXPECT_GT(far_out, 10);
  // No cut-off: nowhere does the ground step by more than its slope allows between neighbours.
  // (Each triangle's vertical extent against its horizontal one: at most 1 in 2 on this site.)
  for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
    const Vertex a = vertex(mesh, mesh.indices[t]), b = vertex(mesh, mesh.indices[t + 1]), c = vertex(mesh, mesh.indices[t + 2]);
    const double rise = std::max({a.z, b.z, c.z}) - std::min({a.z, b.z, c.z});
    const double run = std::max({std::hypot(a.x - b.x, a.y - b.y), std::hypot(b.x - c.x, b.y - c.y), std::hypot(c.x - a.x, c.y - a.y)});
    EXPECT_LT(rise, 0.5 * run + 1e-6) << "triangle at (" << a.x << ", " << a.y << ")";
  }
}

TEST(SiteTerrain, AChartedBreakwaterStandsAtItsCrestAndItsOutlineIsDry) {
  HarbourGrid h = sloping_harbour();
  CoastalStructure s;
  s.name = "mole";
  s.kind = "rubble_mound_breakwater";
  s.lines = {{{kOriginX + 20.0, kOriginY + 40.0}, {kOriginX + 120.0, kOriginY + 40.0}, {kOriginX + 160.0, kOriginY + 80.0}}};
  s.crest_width_m = 6.0;
  s.crest_elevation_m = 2.0;
  s.side_slope = 2.0;
  CoastalStructure quay;
  quay.name = "pier";
  quay.kind = "pier";
  quay.polygons = {{{{kOriginX + 30.0, kOriginY + 70.0}, {kOriginX + 50.0, kOriginY + 70.0}, {kOriginX + 50.0, kOriginY + 100.0},
                     {kOriginX + 30.0, kOriginY + 100.0}, {kOriginX + 30.0, kOriginY + 70.0}}}};
  quay.crest_elevation_m = 1.5;
  h.structures = {s, quay};
  const TerrainMesh mesh = playback::build_site_terrain(h);
  const std::size_t total = mesh.vertices.size() / TerrainMesh::kFloatsPerVertex;
  ASSERT_GT(total, mesh.ground_vertex_count);
  int crest = 0, deck = 0;
  for (std::size_t k = mesh.ground_vertex_count; k < total; ++k) {
    const Vertex v = vertex(mesh, k);
    ASSERT_TRUE(v.material == 1 || v.material == 2);
    if (v.material == 1) {
      EXPECT_LE(v.z, 2.0 + 1e-6);
      crest += std::abs(v.z - 2.0) < 1e-6;
      if (v.z < 0) {  // a toe: on the ground below it, 0.3 m down, reached over the face's 1:2 run
        EXPECT_LT(v.z, -0.3);
      }
    } else {
      EXPECT_LE(v.z, 1.5 + 1e-6);
      deck += std::abs(v.z - 1.5) < 1e-6;
      EXPECT_TRUE(v.x > 30 - 1e-3 && v.x < 50 + 1e-3 && v.y > 70 - 1e-3 && v.y < 100 + 1e-3) << "a vertical wall";
    }
  }
  EXPECT_EQ(crest, 2 * 3);  // both crest edges at the three vertices of the centre line
  EXPECT_EQ(deck, 2 * 4);   // the deck's four corners, and the walls' tops
  // The mask: texels of a quarter cell (1.25 m); dry within the crest plus the faces' run above
  // still water (3 + 2 x 2 = 7 m of the centre line) and inside the pier, wet a texel beyond.
  const Raster<float>& mask = mesh.structure_mask;
  ASSERT_EQ(mask.columns(), 160);
  ASSERT_EQ(mask.rows(), 120);
  auto at = [&](double x, double y) { return mask(int(x / 1.25), int(y / 1.25)); };
  EXPECT_EQ(at(70.0, 40.0), 1.f);
  EXPECT_EQ(at(70.0, 40.0 + 6.0), 1.f);
  EXPECT_EQ(at(70.0, 40.0 - 8.5), 0.f);
  EXPECT_EQ(at(140.0, 60.0), 1.f);  // on the bent arm
  EXPECT_EQ(at(40.0, 85.0), 1.f);   // the pier
  EXPECT_EQ(at(40.0, 102.0), 0.f);
  EXPECT_EQ(at(180.0, 20.0), 0.f);
}

TEST(SiteTerrain, PorousCellsWithoutGeometryAreRaisedAlongTheirSmoothOutline) {
  HarbourGrid h = sloping_harbour();
  for (int i = 5; i < 25; ++i) h.porosity(i, 8) = 0.4f;
  playback::TerrainOptions options;
  options.cell_structure_crest_m = 2.5;
  const TerrainMesh mesh = playback::build_site_terrain(h, options);
  EXPECT_EQ(mesh.vertices.size() / TerrainMesh::kFloatsPerVertex, mesh.ground_vertex_count);
  ASSERT_EQ(mesh.structure_mask.columns(), 40);  // the cells' own flags, read bilinearly
  ASSERT_EQ(mesh.structure_mask.rows(), 30);
  EXPECT_EQ(mesh.structure_mask(10, 8), 1.f);
  EXPECT_EQ(mesh.structure_mask(10, 9), 0.f);
  int raised = 0, untouched = 0;
  for (std::size_t k = 0; k < mesh.ground_vertex_count; ++k) {
    const Vertex v = vertex(mesh, k);
    if (std::abs(v.y - 42.5) < 1e-6 && v.x > 30 && v.x < 120) {  // on row 8's centres: the crest
      EXPECT_NEAR(v.z, 2.5, 1e-6);
      EXPECT_EQ(v.material, 1);
      ++raised;
    }
    if (std::abs(v.y - 52.5) < 1e-6 && v.x > 30 && v.x < 120) {  // two rows north: the seabed
      EXPECT_NEAR(v.z, playback::ground_elevation_m(h, v.x, v.y), 1e-6);
      EXPECT_EQ(v.material, 0);
      ++untouched;
    }
  }
  EXPECT_GT(raised, 30);
  EXPECT_GT(untouched, 30);
}

}  // namespace nearshore

namespace nearshore {
namespace {

// The sloping harbour (200 x 150 m, land 3 m up along its north edge) inside surroundings of 10 m
// cells reaching 200 m beyond it on every side: 10 m deep water to the south with an island 4 m
// high (a disc of 40 m radius) 120 m south of the grid, where the edge's rule says open water; no
// data (NaN) east of x = 330 m (the chart ends there); land 3 m up north of the grid.
HarbourGrid harbour_with_surroundings() {
  HarbourGrid h = sloping_harbour();
  h.surroundings = test::surroundings_round(h.geometry, 10.0, 200.0, [](double x, double y) {
    const double depth = std::hypot(x - 100.0, y + 120.0) < 40.0 ? -4.0 : std::clamp(0.1 * (110.0 - y), -3.0, 10.0);
    return x > 330.0 ? NAN : depth;  // the grid's own slope continued, the island, no data east
  });
  return h;
}

}  // namespace

// Issue 41: the skirt's ground is the surroundings' where they have data: the island south of the
// grid stands at its 4 m (the edge's rule alone puts 16 m of water there), the grid's edge stays
// continuous (the turn to the surroundings starts at zero there), and where they end (no data to
// the east, their box's edge to the south) the skirt is the edge's rule again. Every skirt vertex
// is its twin's ground, the twin of what the shader draws (terrain_render_test.cpp).
TEST(SiteTerrain, TheSkirtTakesTheSurroundingsGroundAndTheEdgesRuleWhereTheyEnd) {
  const HarbourGrid h = harbour_with_surroundings();
  const playback::SurroundingGround ground = playback::surrounding_ground(h);
  const playback::SurroundingGround none;
  ASSERT_FALSE(ground.empty());
  EXPECT_DOUBLE_EQ(ground.cells.origin_x_m, -200.0);  // in the site frame
  EXPECT_DOUBLE_EQ(ground.edge_blend_m, 20.0);
  // The weight: 0 on the box's outer cells and on cells without data, 1 from 4 cells inside.
  EXPECT_EQ(ground.weight(0, 20), 0.f);
  EXPECT_EQ(ground.weight(56, 20), 0.f);  // x = 365 m: no data
  EXPECT_EQ(ground.weight(20, 20), 1.f);
  EXPECT_GT(ground.weight(2, 20), 0.f);
  EXPECT_LT(ground.weight(2, 20), 1.f);
  const auto skirt = [&](const playback::SurroundingGround& g, double x, double y) {
    return playback::skirt_ground_m(h, g, 20.0, x, y);
  };
  // The island, and the edge's rule there.
  EXPECT_NEAR(skirt(ground, 100.0, -120.0), 4.0, 1e-4);
  EXPECT_LT(skirt(none, 100.0, -120.0), -10.0);
  // The sea south of the grid deepens as the surroundings say (10 m), not to the open sea's 20 m.
  EXPECT_NEAR(skirt(ground, 20.0, -150.0), -10.0, 1e-4);
  // Continuous at the grid's edge, on water (south) and on land (north).
  for (double x : {30.0, 100.0, 170.0}) {
    EXPECT_NEAR(skirt(ground, x, -1e-6), playback::ground_elevation_m(h, x, 0.0), 1e-4) << x;
    EXPECT_NEAR(skirt(ground, x, 150.0 + 1e-6), playback::ground_elevation_m(h, x, 150.0), 1e-4) << x;
  }
  // Beyond their data (east of 330 m) and beyond their box: the edge's rule, exactly.
  for (const auto& [x, y] : {std::pair{345.0, 75.0}, {360.0, -100.0}, {100.0, -230.0}, {-300.0, 75.0}, {100.0, 2000.0}})
    EXPECT_EQ(skirt(ground, x, y), skirt(none, x, y)) << x << ", " << y;
  // The mesh: every skirt vertex is the twin's ground; within the surroundings' box its steps are
  // at most their cells (so the island is drawn), beyond it they grow to the skirt's end.
  const TerrainMesh mesh = playback::build_site_terrain(h);
  int on_island = 0;
  double widest_step_south = 0, previous_y = 0;
  bool first = true;
  for (std::size_t k = 0; k < mesh.ground_vertex_count; ++k) {
    const Vertex v = vertex(mesh, k);
    if (v.x >= 0 && v.x <= 200 && v.y >= 0 && v.y <= 150) continue;
    EXPECT_NEAR(v.z, skirt(ground, v.x, v.y), 1e-3 + 1e-6 * std::abs(v.z)) << "(" << v.x << ", " << v.y << ")";
    if (std::hypot(v.x - 100.0, v.y + 120.0) < 25.0) {
      ++on_island;
      EXPECT_GT(v.z, 2.0) << "(" << v.x << ", " << v.y << ")";
    }
    if (v.x > 99.0 && v.x < 101.0) {  // one column of the lattice (x = 100 m)
      if (!first && v.y > -200.0 && v.y <= 0.0) widest_step_south = std::max(widest_step_south, v.y - previous_y);
      previous_y = v.y, first = false;
    }
  }
  EXPECT_GT(on_island, 9);
  EXPECT_LE(widest_step_south, 10.0 + 1e-3);  // float vertices
  EXPECT_EQ(mesh.surroundings.weight.values(), ground.weight.values());
}

}  // namespace nearshore
