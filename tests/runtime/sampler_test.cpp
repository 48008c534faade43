// CPU surface queries (runtime/surface_sampler.hpp): the sampler is the formulas of its header
// (checked against an independent hand evaluation on a snapshot made by hand), the displaced query
// inverts the choppy displacement, the harbour weight's gradient is its derivative, velocity and
// dry cells follow formula 5, and the shown surface is continuous across the rectangle's edge and
// the blending zone.
#include "nearshore/runtime/surface_sampler.hpp"

#include <cmath>
#include <limits>
#include <cstdio>
#include <random>

#include <gtest/gtest.h>

#include "nearshore/runtime/deep_water_source.hpp"
#include "nearshore/runtime/streaming_engine.hpp"
#include "runtime_test_support.hpp"

namespace nearshore::runtime {
namespace {
using namespace testing;
using namespace std::chrono_literals;

constexpr int kColumns = 5, kRows = 4, kTileNodes = 8;
constexpr double kSpacing_m = 3.0;

Raster<float> random_raster(std::mt19937& random, int columns, int rows, float scale) {
  std::uniform_real_distribution<float> uniform(-scale, scale);
  Raster<float> raster(columns, rows);
  for (float& v : raster.values()) v = uniform(random);
  return raster;
}

std::vector<float> random_tile(std::mt19937& random, float scale) {
  std::uniform_real_distribution<float> uniform(-scale, scale);
  std::vector<float> tile(kTileNodes * kTileNodes);
  for (float& v : tile) v = uniform(random);
  return tile;
}

// A 5 x 4 harbour of 3 m cells fading in from the south, two keyframes of random fields, and two
// deep keyframes of two random 8 x 8 cascades (tiles 20 m and 7 m).
SurfaceSnapshot hand_made_snapshot() {
  std::mt19937 random(11);
  auto site = std::make_shared<HarbourSite>();
  GridGeometry geometry;
  geometry.columns = kColumns;
  geometry.rows = kRows;
  geometry.spacing_m = kSpacing_m;
  site->harbour = HarbourGrid::open_water(geometry, 4.0f);
  site->harbour.land(4, 3) = 1;
  site->harbour.still_water_depth_m(4, 3) = -1.0f;
  site->width_m = kColumns * kSpacing_m;
  site->height_m = kRows * kSpacing_m;
  site->source_axis = 1;
  site->inward_sign = 1.0;
  site->source_line_m = 0.0;
  site->blend_start_m = 1.0;
  site->blend_width_m = 4.0;
  site->edge_fade_m = 2.0;
  site->choppiness = 0.8;
  SurfaceSnapshot s;
  s.display_time_s = 1.25;
  s.site = site;
  for (auto* keyframe : {&s.harbour_from, &s.harbour_to}) {
    auto k = std::make_shared<HarbourKeyframe>();
    k->surface_elevation_m = random_raster(random, kColumns, kRows, 0.5f);
    k->flux_x_m2_s = random_raster(random, kColumns, kRows, 2.0f);
    k->flux_y_m2_s = random_raster(random, kColumns, kRows, 2.0f);
    k->breaking = Raster<float>(kColumns, kRows, 0.0f);
    *keyframe = k;
  }
  s.harbour_fraction = 0.3;
  for (auto* keyframe : {&s.deep_from, &s.deep_to}) {
    auto k = std::make_shared<DeepWaterKeyframe>();
    for (double tile : {20.0, 7.0}) {
      ocean::DeepWaterFrame frame;
      frame.grid_size = kTileNodes;
      frame.tile_length_m = tile;
      frame.surface_elevation_m = random_tile(random, 0.4f);
      frame.displacement_x_m = random_tile(random, 0.25f);
      frame.displacement_y_m = random_tile(random, 0.25f);
      frame.slope_x = random_tile(random, 0.1f);
      frame.slope_y = random_tile(random, 0.1f);
      k->cascades.push_back(frame);
    }
    *keyframe = k;
  }
  s.deep_fraction = 0.6;
  return s;
}

// Formula 1, written out again independently of the sampler.
double by_hand_harbour(const Raster<float>& f, double x, double y) {
  const double u = std::clamp(x / kSpacing_m - 0.5, 0.0, kColumns - 1.0);
  const double v = std::clamp(y / kSpacing_m - 0.5, 0.0, kRows - 1.0);
  const int i0 = std::min(static_cast<int>(std::floor(u)), kColumns - 2), j0 = std::min(static_cast<int>(std::floor(v)), kRows - 2);
  const double a = u - i0, b = v - j0;
  return (1 - b) * ((1 - a) * f(i0, j0) + a * f(i0 + 1, j0)) + b * ((1 - a) * f(i0, j0 + 1) + a * f(i0 + 1, j0 + 1));
}

// Formula 2.
double by_hand_tile(const std::vector<float>& f, double tile, double x, double y) {
  const auto wrap = [](long long i) { return static_cast<int>(((i % kTileNodes) + kTileNodes) % kTileNodes); };
  const double u = x / tile * kTileNodes, v = y / tile * kTileNodes;
  const long long i0 = static_cast<long long>(std::floor(u)), j0 = static_cast<long long>(std::floor(v));
  const double a = u - i0, b = v - j0;
  const auto at = [&](long long i, long long j) { return f[static_cast<std::size_t>(wrap(j) * kTileNodes + wrap(i))]; };
  return (1 - b) * ((1 - a) * at(i0, j0) + a * at(i0 + 1, j0)) + b * ((1 - a) * at(i0, j0 + 1) + a * at(i0 + 1, j0 + 1));
}

double by_hand_deep(const SurfaceSnapshot& s, const std::vector<float> ocean::DeepWaterFrame::*channel, double x, double y) {
  double from = 0, to = 0;
  for (std::size_t c = 0; c < s.deep_from->cascades.size(); ++c) {
    from += by_hand_tile(s.deep_from->cascades[c].*channel, s.deep_from->cascades[c].tile_length_m, x, y);
    to += by_hand_tile(s.deep_to->cascades[c].*channel, s.deep_to->cascades[c].tile_length_m, x, y);
  }
  return (1 - s.deep_fraction) * from + s.deep_fraction * to;
}

double by_hand_shown(const SurfaceSnapshot& s, double x, double y) {
  const double w = harbour_weight(*s.site, x, y);
  const double harbour = (1 - s.harbour_fraction) * by_hand_harbour(s.harbour_from->surface_elevation_m, x, y) +
                         s.harbour_fraction * by_hand_harbour(s.harbour_to->surface_elevation_m, x, y);
  return w * harbour + (1 - w) * by_hand_deep(s, &ocean::DeepWaterFrame::surface_elevation_m, x, y);
}

TEST(SurfaceSampler, IsTheFormulasOfItsHeader) {
  const SurfaceSnapshot s = hand_made_snapshot();
  const SurfaceSampler sampler(s);
  std::mt19937 random(3);
  std::uniform_real_distribution<double> x(-25.0, 40.0), y(-25.0, 35.0);
  std::vector<SitePoint> points = {{0, 0}, {15, 12}, {1.5, 1.5}, {13.5, 10.5}, {7.5, 0.0}, {7.5, 12.0}, {-20.0, 3.0},
                                   {7.5, 5.0}, {14.9, 6.0}, {100000.3, -70000.1}};
  for (int i = 0; i < 2000; ++i) points.push_back({x(random), y(random)});
  std::vector<double> batched(points.size());
  sampler.elevations_m(points, batched, ChoppyPoint::kLattice);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double expected = by_hand_shown(s, points[i].x_m, points[i].y_m);
    // Both in double from the same float texels: equal to round-off (x / L against x * (1 / L):
    // at 100 km a few 1e-12 of a tile node).
    EXPECT_NEAR(sampler.elevation_m(points[i].x_m, points[i].y_m, ChoppyPoint::kLattice), expected, 1e-10)
        << points[i].x_m << ", " << points[i].y_m;
    EXPECT_EQ(batched[i], sampler.elevation_m(points[i].x_m, points[i].y_m, ChoppyPoint::kLattice));
    EXPECT_NEAR(sampler.state(points[i].x_m, points[i].y_m, ChoppyPoint::kLattice).surface_elevation_m, expected, 1e-10);
  }
  // The weight: 0 outside and on the source side before the zone, 1/2 mid-zone (far from the
  // other edges), 1 inside beyond every fade.
  EXPECT_EQ(harbour_weight(*s.site, -0.1, 6.0), 0.0);
  EXPECT_EQ(harbour_weight(*s.site, 7.5, 0.9), 0.0);
  EXPECT_NEAR(harbour_weight(*s.site, 7.5, 3.0), 0.5, 1e-12);
  EXPECT_EQ(harbour_weight(*s.site, 7.5, 7.0), 1.0);
  // A NaN coordinate gives a weight, not a read outside the table.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(harbour_weight(*s.site, nan, 3.0), 0.0);
  EXPECT_TRUE(std::isfinite(harbour_weight_and_gradient(*s.site, 7.5, nan).d_dy_per_m));
}

TEST(SurfaceSampler, HarbourWeightGradientIsItsDerivative) {
  const SurfaceSnapshot s = hand_made_snapshot();
  std::mt19937 random(5);
  std::uniform_real_distribution<double> x(0.01, 14.99), y(0.01, 11.99);
  for (int i = 0; i < 2000; ++i) {
    const double px = x(random), py = y(random), h = 1e-6;
    const HarbourWeight w = harbour_weight_and_gradient(*s.site, px, py);
    EXPECT_DOUBLE_EQ(w.weight, harbour_weight(*s.site, px, py));
    // Central differences: error O(h^2 w''') ~ 1e-12 plus round-off 1e-16 / h.
    const double dx = (harbour_weight(*s.site, px + h, py) - harbour_weight(*s.site, px - h, py)) / (2 * h);
    const double dy = (harbour_weight(*s.site, px, py + h) - harbour_weight(*s.site, px, py - h)) / (2 * h);
    EXPECT_NEAR(w.d_dx_per_m, dx, 1e-7) << px << ", " << py;
    EXPECT_NEAR(w.d_dy_per_m, dy, 1e-7) << px << ", " << py;
  }
}

TEST(SurfaceSampler, DisplacedQueriesInvertTheChoppyDisplacement) {
  const SurfaceSnapshot s = hand_made_snapshot();
  const SurfaceSampler sampler(s);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> x(-20.0, 35.0), y(-20.0, 30.0);
  double largest_residual = 0.0, largest_move = 0.0;
  for (int i = 0; i < 2000; ++i) {
    const SitePoint q{x(random), y(random)};
    const SitePoint p = sampler.lattice_point(q.x_m, q.y_m);
    // p + (1 - w(p)) lambda D(p) = q (formula 4).
    const double fade = 1.0 - harbour_weight(*s.site, p.x_m, p.y_m);
    const double dx = by_hand_deep(s, &ocean::DeepWaterFrame::displacement_x_m, p.x_m, p.y_m);
    const double dy = by_hand_deep(s, &ocean::DeepWaterFrame::displacement_y_m, p.x_m, p.y_m);
    const double residual = std::hypot(p.x_m + fade * 0.8 * dx - q.x_m, p.y_m + fade * 0.8 * dy - q.y_m);
    largest_residual = std::max(largest_residual, residual);
    largest_move = std::max(largest_move, std::hypot(p.x_m - q.x_m, p.y_m - q.y_m));
    // eta(q) = eta(p), D_eta read from the query layout (int16 of scale max|v| / 32767: each of
    // the 2 cascades moves by at most 0.4 m / 32767 / 2 = 6e-6 m) plus float round-off.
    EXPECT_NEAR(sampler.elevation_m(q.x_m, q.y_m), sampler.elevation_m(p.x_m, p.y_m, ChoppyPoint::kLattice), 2e-5);
  }
  // The iteration stops at the first point whose residual, on the query layout, is within the
  // tolerance; on the float fields it differs by the rounding of D (2 cascades x 0.25 m / 32767 / 2
  // x lambda 0.8 = 6e-6 m).
  EXPECT_LT(largest_residual, kDisplacementTolerance_m + 1e-5);
  EXPECT_GT(largest_move, 0.1);  // the displacement is not negligible
  // A batch (blocks solved side by side) gives the single queries' heights bit for bit.
  std::vector<SitePoint> hull;
  for (int i = 0; i < 400; ++i) hull.push_back({-15.0 + 0.11 * i, -8.0 + 0.07 * i});
  std::vector<double> batch(hull.size());
  sampler.elevations_m(hull, batch);
  for (std::size_t i = 0; i < hull.size(); ++i) EXPECT_EQ(batch[i], sampler.elevation_m(hull[i].x_m, hull[i].y_m)) << i;
}

// The fast displaced query (query layout, residual tolerance, blocks) against a solve of formula 4
// written out here on the float fields and converged to 1e-10 m, at 20 000 points of a Beaufort 5
// sea (3 cascades of 256^2, lambda 1: the benchmark's sea) on the open sea and across the blending
// zone of a harbour of linear waves. Accepted: 1 mm of height. The solve's own bound is 0.1 mm
// horizontally (its tolerance) times the displaced surface's slope, plus the int16 rounding
// (below 0.05 mm for this sea); 1 mm is a thousandth of this sea's wave height and below what a
// hull's heave or a buoyancy integral resolves.
TEST(SurfaceSampler, DisplacedQueriesMatchAConvergedSolve) {
  constexpr int kSize = 64;
  constexpr double kCell_m = 8.0;
  auto site = std::make_shared<HarbourSite>();
  GridGeometry geometry;
  geometry.columns = geometry.rows = kSize;
  geometry.spacing_m = kCell_m;
  site->harbour = HarbourGrid::open_water(geometry, 12.0f);
  site->width_m = site->height_m = kSize * kCell_m;
  site->source_axis = 1;
  site->source_line_m = 40.0;
  site->blend_start_m = 20.0;
  site->blend_width_m = 80.0;
  site->edge_fade_m = 60.0;
  SurfaceSnapshot s;
  s.site = site;
  for (int which = 0; which < 2; ++which) {
    auto keyframe = std::make_shared<HarbourKeyframe>();
    keyframe->surface_elevation_m = Raster<float>(kSize, kSize, 0.0f);
    for (int row = 0; row < kSize; ++row)
      for (int column = 0; column < kSize; ++column)
        keyframe->surface_elevation_m(column, row) =
            static_cast<float>(0.8 * std::cos(0.08 * column * kCell_m + 0.02 * row * kCell_m - 0.3 * which));
    (which == 0 ? s.harbour_from : s.harbour_to) = keyframe;
  }
  s.harbour_fraction = 0.4;
  const BeaufortSea sea{.force = 5, .grid_size = 256, .cascade_count = 3, .shortest_wavelength_m = 0.5};
  const auto field = build_beaufort_field(sea);
  site->choppiness = sea.choppiness;
  for (int which = 0; which < 2; ++which) {
    auto keyframe = std::make_shared<DeepWaterKeyframe>();
    const ocean::TimedWeight at{12.0 + which / 30.0, 1.0};
    field->synthesise_into(std::span<const ocean::TimedWeight>(&at, 1), keyframe->cascades);
    if (which == 0) pack_query_tiles(*keyframe);  // one keyframe packed as the engine does, one by the sampler
    (which == 0 ? s.deep_from : s.deep_to) = keyframe;
  }
  s.deep_fraction = 0.25;
  const SurfaceSampler sampler(s);

  // Formula 2 for any tile, and D (both keyframes, in time) on the float channels.
  const auto tile_value = [](const ocean::DeepWaterFrame& frame, const std::vector<float>& f, double x, double y) {
    const int n = frame.grid_size;
    const double u = (x / frame.tile_length_m - std::floor(x / frame.tile_length_m)) * n;
    const double v = (y / frame.tile_length_m - std::floor(y / frame.tile_length_m)) * n;
    const int i0 = std::min(static_cast<int>(u), n - 1), j0 = std::min(static_cast<int>(v), n - 1);
    const int i1 = (i0 + 1) % n, j1 = (j0 + 1) % n;
    const double a = u - i0, b = v - j0;
    const auto at = [&](int i, int j) { return static_cast<double>(f[static_cast<std::size_t>(j) * n + i]); };
    return (1 - b) * ((1 - a) * at(i0, j0) + a * at(i1, j0)) + b * ((1 - a) * at(i0, j1) + a * at(i1, j1));
  };
  const auto shift = [&](double x, double y, double& sx, double& sy) {  // (1 - w) lambda D(p)
    double from_x = 0, from_y = 0, to_x = 0, to_y = 0;
    for (std::size_t c = 0; c < s.deep_from->cascades.size(); ++c) {
      const auto& a = s.deep_from->cascades[c];
      const auto& b = s.deep_to->cascades[c];
      from_x += tile_value(a, a.displacement_x_m, x, y);
      from_y += tile_value(a, a.displacement_y_m, x, y);
      to_x += tile_value(b, b.displacement_x_m, x, y);
      to_y += tile_value(b, b.displacement_y_m, x, y);
    }
    const double fade = 1.0 - harbour_weight(*site, x, y);
    sx = fade * sea.choppiness * ((1 - s.deep_fraction) * from_x + s.deep_fraction * to_x);
    sy = fade * sea.choppiness * ((1 - s.deep_fraction) * from_y + s.deep_fraction * to_y);
  };
  // The reference: Newton on F(p) = p + shift(p) - q with a central-difference Jacobian (h = 1 mm,
  // inside a tile cell of 0.25 m mostly; where a step crosses a node the next step corrects it)
  // and damping by halves when |F| does not fall, until |F| < 1e-10 m.
  const auto reference = [&](SitePoint q, SitePoint& p) {
    p = q;
    for (int iteration = 0; iteration < 100; ++iteration) {
      double sx, sy;
      shift(p.x_m, p.y_m, sx, sy);
      const double fx = p.x_m + sx - q.x_m, fy = p.y_m + sy - q.y_m;
      const double residual = std::hypot(fx, fy);
      if (residual < 1e-10) return true;
      const double h = 1e-3;
      double ax, ay, bx, by, cx, cy, dx, dy;
      shift(p.x_m + h, p.y_m, ax, ay);
      shift(p.x_m - h, p.y_m, bx, by);
      shift(p.x_m, p.y_m + h, cx, cy);
      shift(p.x_m, p.y_m - h, dx, dy);
      const double jxx = 1 + (ax - bx) / (2 * h), jyx = (ay - by) / (2 * h), jxy = (cx - dx) / (2 * h), jyy = 1 + (cy - dy) / (2 * h);
      const double det = jxx * jyy - jxy * jyx;
      double step_x = -fx, step_y = -fy;
      if (det > 0.05) {
        step_x = -(jyy * fx - jxy * fy) / det;
        step_y = -(-jyx * fx + jxx * fy) / det;
      }
      for (double scale = 1.0; scale > 1e-3; scale *= 0.5) {
        const SitePoint trial{p.x_m + scale * step_x, p.y_m + scale * step_y};
        shift(trial.x_m, trial.y_m, sx, sy);
        if (std::hypot(trial.x_m + sx - q.x_m, trial.y_m + sy - q.y_m) < residual || scale < 2e-3) {
          p = trial;
          break;
        }
      }
    }
    return false;
  };
  std::mt19937 random(3);
  std::uniform_real_distribution<double> along(-400.0, kSize * kCell_m + 400.0), open(-400.0, -20.0), zone(0.0, 150.0);
  std::vector<SitePoint> points;
  for (int i = 0; i < 10000; ++i) points.push_back({along(random), open(random)});   // deep water alone
  for (int i = 0; i < 10000; ++i) points.push_back({along(random), zone(random)});   // blending zone and edge fades
  std::vector<double> batch(points.size());
  sampler.elevations_m(points, batch);
  double largest_error_m = 0.0, largest_move_m = 0.0;
  int converged = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    SitePoint p;
    if (!reference(points[i], p)) continue;  // a folding crest: no unique surface point to compare
    ++converged;
    const double exact = sampler.elevation_m(p.x_m, p.y_m, ChoppyPoint::kLattice);
    largest_error_m = std::max(largest_error_m, std::abs(batch[i] - exact));
    largest_move_m = std::max(largest_move_m, std::hypot(p.x_m - points[i].x_m, p.y_m - points[i].y_m));
    EXPECT_EQ(batch[i], sampler.elevation_m(points[i].x_m, points[i].y_m)) << i;  // batch = single, bit for bit
  }
  EXPECT_GT(converged, 19800);
  EXPECT_GT(largest_move_m, 0.3);  // the choppy displacement matters at this sea
  EXPECT_LT(largest_error_m, 1e-3);
  std::printf("displaced query vs converged solve: %d points, largest error %.4f mm, largest displacement %.2f m\n",
              converged, 1e3 * largest_error_m, largest_move_m);
}

TEST(SurfaceSampler, VelocityIsFluxOverTotalDepthAndLandIsDry) {
  const SurfaceSnapshot s = hand_made_snapshot();
  const SurfaceSampler sampler(s);
  // Cell (2, 2) centre: w = 1 there (beyond the zone and every fade).
  const double x = 2.5 * kSpacing_m, y = 2.5 * kSpacing_m, f = s.harbour_fraction;
  ASSERT_EQ(harbour_weight(*s.site, x, y), 1.0);
  const SurfaceState state = sampler.state(x, y, ChoppyPoint::kLattice);
  const double eta = (1 - f) * s.harbour_from->surface_elevation_m(2, 2) + f * s.harbour_to->surface_elevation_m(2, 2);
  const double p = (1 - f) * s.harbour_from->flux_x_m2_s(2, 2) + f * s.harbour_to->flux_x_m2_s(2, 2);
  const double q = (1 - f) * s.harbour_from->flux_y_m2_s(2, 2) + f * s.harbour_to->flux_y_m2_s(2, 2);
  EXPECT_NEAR(state.surface_elevation_m, eta, 1e-12);
  EXPECT_NEAR(state.velocity_x_m_s, p / (4.0 + eta), 1e-12);
  EXPECT_NEAR(state.velocity_y_m_s, q / (4.0 + eta), 1e-12);
  EXPECT_FALSE(state.dry);
  EXPECT_NEAR(std::hypot(state.normal_x, state.normal_y, state.normal_z), 1.0, 1e-12);
  // Central differences at the texel: the slope at a texel centre is exactly that.
  const auto& a = s.harbour_from->surface_elevation_m;
  const auto& b = s.harbour_to->surface_elevation_m;
  EXPECT_NEAR(state.slope_x, ((1 - f) * (a(3, 2) - a(1, 2)) + f * (b(3, 2) - b(1, 2))) / (2 * kSpacing_m), 1e-12);
  // The land cell (4, 3) is dry and still.
  const SurfaceState land = sampler.state(4.5 * kSpacing_m - 0.2, 3.5 * kSpacing_m - 0.2, ChoppyPoint::kLattice);
  EXPECT_TRUE(land.dry);
  EXPECT_GT(land.harbour_weight, 0.0);
  EXPECT_EQ(land.velocity_x_m_s, 0.0);  // dry harbour, and a deep water without currents
  EXPECT_EQ(land.velocity_y_m_s, 0.0);
  // Beyond the harbour, no flux channels in this deep water: no current, never dry.
  const SurfaceState open = sampler.state(-30.0, 50.0);
  EXPECT_EQ(open.velocity_x_m_s, 0.0);
  EXPECT_FALSE(open.dry);
}

// Along a line, the shown surface changes between neighbouring points no faster than its slope
// allows: a step (a visible edge) would change by a fixed amount however close the points are.
// The bound is 2 x the largest |slope| on the line: a bilinear interpolant's derivative differs
// from the interpolated central differences by at most that factor on resolved waves.
void expect_continuous_along(const SurfaceSampler& sampler, SitePoint from, SitePoint to, ChoppyPoint point,
                             const char* what) {
  constexpr int kSamples = 6000;
  const double length = std::hypot(to.x_m - from.x_m, to.y_m - from.y_m), h = length / kSamples;
  double steepest = 0.0, largest_step = 0.0, previous = 0.0;
  for (int i = 0; i <= kSamples; ++i) {
    const double u = static_cast<double>(i) / kSamples;
    const double x = from.x_m + u * (to.x_m - from.x_m), y = from.y_m + u * (to.y_m - from.y_m);
    const SurfaceState state = sampler.state(x, y, ChoppyPoint::kLattice);
    steepest = std::max(steepest, std::hypot(state.slope_x, state.slope_y));
    const double eta = sampler.elevation_m(x, y, point);
    if (i > 0) largest_step = std::max(largest_step, std::abs(eta - previous));
    previous = eta;
  }
  const double allowed = (point == ChoppyPoint::kLattice ? 2.0 : 4.0) * steepest * h;
  EXPECT_LE(largest_step, allowed) << what << ": step " << largest_step << " m over " << h << " m, slope " << steepest;
  EXPECT_GT(steepest, 0.0) << what;
}

TEST(SurfaceSampler, TheSurfaceIsContinuousAcrossTheRectangleEdgeAndTheBlendingZone) {
  const fs::path folder = scratch_folder();
  // 64 x 48 cells of 2 m: a harbour 128 m x 96 m of linear waves, in a Beaufort 4 sea of its own
  // (uncorrelated with the harbour: the hardest case for a seam).
  write_wave_sequence(folder, wave_geometry(64, 48, 2.0), {{0.4, 0.25, 0.08, 1.6, 0.0}, {0.2, 0.1, -0.3, 1.8, 2.0}},
                      6, 0.1);
  StreamingOptions options;
  options.plan = PlanKind::kFrameOrder;
  options.deep_water = DeepWaterChoice::kBeaufort;
  options.beaufort = {.force = 4, .grid_size = 64, .cascade_count = 2, .shortest_wavelength_m = 1.0};
  options.edge_fade_m = 12.0;
  StreamingEngine engine(folder, options);
  ASSERT_TRUE(engine.wait_until_ready(0.25, 20s));
  engine.advance_to(0.25);
  const SurfaceSampler sampler(engine.snapshot());
  const HarbourSite& site = *engine.site();
  EXPECT_EQ(site.width_m, 128.0);
  // Across the west edge, the north edge, the south-east corner and through the whole rectangle.
  for (ChoppyPoint point : {ChoppyPoint::kLattice, ChoppyPoint::kDisplaced}) {
    expect_continuous_along(sampler, {-20.0, 40.0}, {30.0, 40.0}, point, "west edge");
    expect_continuous_along(sampler, {70.0, 70.0}, {70.0, 120.0}, point, "north edge");
    expect_continuous_along(sampler, {100.0, 20.0}, {150.0, -20.0}, point, "south-east corner");
    expect_continuous_along(sampler, {-10.0, -10.0}, {140.0, 110.0}, point, "diagonal");
  }
  // And the two fields do differ there (the test would be empty otherwise).
  EXPECT_GT(std::abs(sampler.harbour_elevation_m(64.0, 48.0) - sampler.deep_elevation_m(64.0, 48.0)), 0.01);
}

// Issue 15: rectangular cells (dx = 2 m, dy = 5 m). A surface linear in x and y is reproduced
// exactly by formula 1 on (x / dx, y / dy), and its slope (formula 6, central differences divided
// by each axis' own spacing) is exactly the plane's; a sampler that used dx along y would put the
// crest of every cell row 2.5 times too far north and get d eta / dy wrong by the same factor.
TEST(SurfaceSampler, RectangularCellsInterpolateOnEachAxisSpacing) {
  constexpr double kDx = 2.0, kDy = 5.0, kEta0 = 0.3, kSlopeX = 0.01, kSlopeY = -0.004;
  auto site = std::make_shared<HarbourSite>();
  GridGeometry geometry;
  geometry.columns = 8;
  geometry.rows = 6;
  geometry.set_spacing(kDx, kDy);
  site->harbour = HarbourGrid::open_water(geometry, 4.0f);
  site->width_m = geometry.width_m();
  site->height_m = geometry.height_m();
  site->edge_fade_m = 1.0;  // the interior below is beyond every ramp: w = 1
  SurfaceSnapshot s;
  s.site = site;
  auto keyframe = std::make_shared<HarbourKeyframe>();
  keyframe->surface_elevation_m = Raster<float>(geometry.columns, geometry.rows);
  for (int row = 0; row < geometry.rows; ++row)
    for (int column = 0; column < geometry.columns; ++column)
      keyframe->surface_elevation_m(column, row) = static_cast<float>(
          kEta0 + kSlopeX * geometry.cell_centre_x_m(column) + kSlopeY * geometry.cell_centre_y_m(row));
  keyframe->flux_x_m2_s = keyframe->flux_y_m2_s = keyframe->breaking = Raster<float>(geometry.columns, geometry.rows, 0.0f);
  s.harbour_from = s.harbour_to = keyframe;
  const SurfaceSampler sampler(s);
  for (double x : {3.0, 5.5, 8.1, 12.9})
    for (double y : {6.0, 11.3, 17.5, 23.9}) {
      const double plane = kEta0 + kSlopeX * x + kSlopeY * y;
      EXPECT_NEAR(sampler.harbour_elevation_m(x, y), plane, 1e-6) << x << ", " << y;  // float texels
      const SurfaceState state = sampler.state(x, y, ChoppyPoint::kLattice);
      EXPECT_DOUBLE_EQ(state.harbour_weight, 1.0);
      EXPECT_NEAR(state.slope_x, kSlopeX, 1e-6) << x << ", " << y;
      EXPECT_NEAR(state.slope_y, kSlopeY, 1e-6) << x << ", " << y;
    }
}

}  // namespace
}  // namespace nearshore::runtime
