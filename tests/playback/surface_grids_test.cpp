// The grids' CPU logic (no GPU): the radial grid follows seed 000 eq. 2.20, the quadtree's joins
// conform after the CDLOD morph for every pair of neighbouring patches, and the projected grid
// meets the sphere where geometry says and stops at its horizon.
#include "nearshore/playback/surface_grids.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <set>
#include <utility>

#include "nearshore/core/error.hpp"

namespace {
using namespace nearshore;
using namespace nearshore::playback;

CameraView view_from(Vector3 eye, Vector3 target, int width = 640, int height = 360, double far = 4e5) {
  Camera camera;
  camera.eye_m = eye;
  camera.target_m = target;
  return camera_view(camera, width, height, 0.5, far);
}

// The vertices of `patch` along one of its edges after the morph, as exact float pairs, keeping
// those inside the segment [lo, hi] of the edge's running coordinate.
std::set<std::pair<float, float>> edge_vertices(const QuadtreeSelection& s, const QuadtreePatch& patch, int edge,
                                                double lo, double hi, const Vector3& eye) {
  std::set<std::pair<float, float>> out;
  const int k = s.patch_quads;
  const double spacing = s.levels[std::size_t(patch.level)].vertex_spacing_m;
  for (int n = 0; n <= k; ++n) {
    const int gx = edge == 0 ? 0 : edge == 1 ? k : n;  // 0 west, 1 east, 2 south, 3 north
    const int gy = edge == 2 ? 0 : edge == 3 ? k : n;
    const double along = (edge < 2 ? patch.origin_y_m + gy * spacing : patch.origin_x_m + gx * spacing);
    if (along < lo || along > hi) continue;
    const auto p = quadtree_vertex(s, patch, gx, gy, eye);
    out.insert({p[0], p[1]});
  }
  return out;
}
}  // namespace

TEST(RadialGrid, RingsFollowEquation220AndReachTheOuterRadius) {
  RadialGridSettings settings;
  settings.segment_count = 64;
  settings.inner_spacing_m = 1.0;
  settings.outer_radius_m = 5000.0;
  const RadialGrid grid = build_radial_grid(settings);
  ASSERT_EQ(grid.vertex_count(), std::size_t(grid.ring_count) * 64);
  const double g = 2 * std::numbers::pi / 64;
  for (int i : {1, 2, 7}) {
    const std::size_t first = std::size_t(i) * 64 * 2;
    EXPECT_NEAR(grid.polar[first], (std::pow(1 + g, i) - 1) / g, 1e-4) << "ring " << i;  // R_i = s((1+g)^i - 1)/g
    EXPECT_NEAR(grid.polar[first + 1], std::numbers::pi * i / 64, 1e-6) << "eq. 2.20 turns ring i by pi i / M";
    EXPECT_NEAR(grid.polar[first + 3] - grid.polar[first + 1], 2 * std::numbers::pi / 64, 1e-6);
  }
  EXPECT_FLOAT_EQ(grid.polar[(grid.vertex_count() - 1) * 2], 5000.f);
  // Far out the cells are square: radial step = arc step.
  const std::size_t ring = std::size_t(grid.ring_count - 3);
  const double radial_step = grid.polar[(ring + 1) * 128] - grid.polar[ring * 128];
  EXPECT_NEAR(radial_step / (g * grid.polar[ring * 128]), 1.0, 0.05);
  EXPECT_EQ(grid.triangles.size(), std::size_t(grid.ring_count - 1) * 64 * 6);
  EXPECT_THROW(build_radial_grid({4, 1.0, 100.0}), nearshore::Error);
}

TEST(QuadtreeGrid, EveryJoinBetweenPatchesConformsAfterTheMorph) {
  QuadtreeSettings settings;
  settings.finest_spacing_m = 0.5;
  settings.patch_quads = 8;
  settings.screen_error_px = 4.0;
  settings.reach_m = 6000.0;
  // Low and high eyes, looking along and across the axes, at positions off the node lattice.
  const std::vector<std::pair<Vector3, Vector3>> cameras = {
      {{13.3, -7.9, 6.0}, {300.0, 250.0, 0.0}}, {{-517.2, 233.1, 40.0}, {-100.0, -50.0, 0.0}},
      {{1000.1, 999.7, 300.0}, {1000.0, 2500.0, 0.0}}, {{71.0, 3.0, 2.0}, {71.0, -500.0, -30.0}}};
  for (const auto& [eye, target] : cameras) {
    const CameraView view = view_from(eye, target, 320, 180, 2e4);
    const QuadtreeSelection s = select_quadtree(settings, view);
    ASSERT_GT(s.patches.size(), 20u);
    std::set<int> levels_used;
    int joins = 0, joins_across_levels = 0;
    for (std::size_t a = 0; a < s.patches.size(); ++a) {
      const QuadtreePatch& pa = s.patches[a];
      levels_used.insert(pa.level);
      const double sa = s.levels[std::size_t(pa.level)].patch_size_m;
      for (std::size_t b = 0; b < s.patches.size(); ++b) {
        if (a == b) continue;
        const QuadtreePatch& pb = s.patches[b];
        const double sb = s.levels[std::size_t(pb.level)].patch_size_m;
        // Patches never overlap.
        const double overlap_x = std::min(pa.origin_x_m + sa, pb.origin_x_m + sb) - std::max(pa.origin_x_m, pb.origin_x_m);
        const double overlap_y = std::min(pa.origin_y_m + sa, pb.origin_y_m + sb) - std::max(pa.origin_y_m, pb.origin_y_m);
        ASSERT_FALSE(overlap_x > 0 && overlap_y > 0) << "patches " << a << " and " << b << " overlap";
        // A shared edge: b east of a (a's edge 1 against b's edge 0) or north of it (3 against 2).
        for (int direction = 0; direction < 2; ++direction) {
          const bool touching = direction == 0 ? pa.origin_x_m + sa == pb.origin_x_m && overlap_y > 0
                                               : pa.origin_y_m + sa == pb.origin_y_m && overlap_x > 0;
          if (!touching) continue;
          ++joins;
          EXPECT_LE(std::abs(pa.level - pb.level), 1) << "neighbours differ by more than one level";
          if (pa.level != pb.level) ++joins_across_levels;
          const double lo = direction == 0 ? std::max(pa.origin_y_m, pb.origin_y_m) : std::max(pa.origin_x_m, pb.origin_x_m);
          const double hi = lo + (direction == 0 ? overlap_y : overlap_x);
          const auto from_a = edge_vertices(s, pa, direction == 0 ? 1 : 3, lo, hi, eye);
          const auto from_b = edge_vertices(s, pb, direction == 0 ? 0 : 2, lo, hi, eye);
          // Conforming: both sides put their (deduplicated) edge vertices at the same points, so
          // the two edges are one polyline, bit for bit, and no pixel can fall between them.
          EXPECT_EQ(from_a, from_b) << "join of level " << pa.level << " at (" << pa.origin_x_m << ", " << pa.origin_y_m
                                    << ") with level " << pb.level << " at (" << pb.origin_x_m << ", " << pb.origin_y_m << ")";
        }
      }
    }
    EXPECT_GE(levels_used.size(), 3u) << "the camera should see several levels";
    EXPECT_GT(joins_across_levels, 4) << "of " << joins << " joins";
  }
}

TEST(QuadtreeGrid, RangesFollowTheScreenSpaceError) {
  QuadtreeSettings settings;
  settings.finest_spacing_m = 0.25;
  settings.patch_quads = 16;
  settings.screen_error_px = 1.0;
  const CameraView view = view_from({0, 0, 20}, {0, 100, 0}, 1280, 720);
  const QuadtreeSelection fine = select_quadtree(settings, view);
  // range_0 = spacing * focal / error: a level-0 quad spans one pixel where level 0 ends.
  EXPECT_NEAR(fine.levels[0].range_m, 0.25 * view.focal_length_px / 1.0, 1e-9);
  EXPECT_NEAR(fine.levels[3].range_m, 8 * fine.levels[0].range_m, 1e-9);
  EXPECT_GE(fine.levels.back().range_m, settings.reach_m);
  settings.screen_error_px = 8.0;
  const QuadtreeSelection coarse = select_quadtree(settings, view);
  EXPECT_LT(coarse.vertex_count(), fine.vertex_count() / 4);
  // Never below 4 node sizes, whatever the error asked (the joins need it).
  settings.screen_error_px = 1000.0;
  EXPECT_NEAR(select_quadtree(settings, view).levels[0].range_m, 4 * 2 * 16 * 0.25, 1e-9);
  settings.patch_quads = 7;
  EXPECT_THROW(select_quadtree(settings, view), nearshore::Error);
}

TEST(ProjectedGrid, RaysMeetTheSphereAndStopAtItsHorizon) {
  const double r = kEarthRadiusM, h = 10000.0;
  const double dip = horizon_dip_rad(h, r);
  EXPECT_NEAR(dip, std::acos(r / (r + h)), 1e-9);
  EXPECT_NEAR(horizon_distance_m(h, r), std::sqrt((r + h) * (r + h) - r * r), 1e-3);
  // Looking horizontally north: the screen row of a depression angle a is ndc_y = -tan(a)/tan(fov/2).
  const CameraView view = view_from({500, 200, h}, {500, 100200, h}, 640, 360, 5e5);
  const double tan_half = std::tan(22.5 * std::numbers::pi / 180);
  auto ndc_of = [&](double depression) { return -std::tan(depression) / tan_half; };
  // Just below the horizon: a hit, on the sphere, at the tangent distance nearly.
  const SpherePoint below = project_to_sphere(view, 0.0, ndc_of(dip + 1e-4), r);
  EXPECT_FALSE(below.on_horizon);
  const double rho = std::hypot(below.x_m - 500, below.y_m - 200);
  EXPECT_NEAR(below.z_m, -curvature_drop_m(rho, r), 1e-3 * rho / 1e5) << "the point lies on the sphere";
  // The chord from the eye along depression a: t = (R + h) sin a - sqrt(R^2 - ((R + h) cos a)^2).
  const double a = dip + 1e-4;
  const double chord = (r + h) * std::sin(a) - std::sqrt(r * r - std::pow((r + h) * std::cos(a), 2));
  EXPECT_NEAR(std::hypot(rho, h - below.z_m), chord, 1.0);
  EXPECT_LT(chord, horizon_distance_m(h, r));
  // Just above: turned down to the horizon, straight ahead.
  const SpherePoint above = project_to_sphere(view, 0.0, ndc_of(dip - 1e-4), r);
  EXPECT_TRUE(above.on_horizon);
  EXPECT_NEAR(above.x_m, 500.0, 1e-6);
  EXPECT_NEAR(std::hypot(above.y_m - 200, h - above.z_m), horizon_distance_m(h, r), 1e-3);
  // Steeply down: the sphere and the flat plane nearly agree (drop of rho^2 / 2R).
  const SpherePoint near_point = project_to_sphere(view, 0.0, -0.99, r);
  const double depression = std::atan(0.99 * tan_half);
  EXPECT_NEAR(near_point.y_m - 200, h / std::tan(depression), 0.01 * h / std::tan(depression));
  // The grid's rows end just above the horizon's row (its margin), never in the open sky.
  const ProjectedGridLayout layout = layout_projected_grid(ProjectedGridSettings{}, view);
  EXPECT_NEAR(layout.ndc_y1, ndc_of(dip) + ProjectedGridSettings{}.margin_ndc, 1e-3);
  EXPECT_GT(layout.vertex_count(), 1000);
  // Looking up into the sky: no sea, no vertices.
  const CameraView up = view_from({0, 0, 10}, {0, 100, 80}, 640, 360);
  EXPECT_EQ(layout_projected_grid(ProjectedGridSettings{}, up).vertex_count(), 0);
}

TEST(ProjectedGrid, CurvatureDropIsStableFromCentimetresToTheHorizon) {
  const double r = kEarthRadiusM;
  for (double rho : {0.01, 1.0, 1e3, 1e5, 3.5e5}) {
    const double exact = r - std::sqrt(r * r - rho * rho);  // fine in double at these distances
    EXPECT_NEAR(curvature_drop_m(rho, r), exact, 1e-9 + 1e-9 * exact) << rho;
    // rho^2 / 2R is its first term; the next is rho^4 / 8R^3, a relative (rho / 2R)^2.
    EXPECT_NEAR(curvature_drop_m(rho, r), rho * rho / (2 * r), exact * std::pow(rho / r, 2)) << rho;
  }
  EXPECT_EQ(grid_kind_from_name("projected"), GridKind::projected);
  EXPECT_THROW(grid_kind_from_name("hexagonal"), nearshore::Error);
}
