#pragma once
// Snapshots built by hand for the renderer's tests: a harbour site with land, a breakwater and a
// blend zone, harbour keyframes holding a known analytic field, and deep-water keyframes from a
// real ocean::DeepWaterField. The CPU side of every comparison is runtime::SurfaceSampler.
#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>

#include "nearshore/ocean/deep_water.hpp"
#include "nearshore/ocean/sea_state_beaufort.hpp"
#include "nearshore/runtime/surface_snapshot.hpp"

namespace nearshore::test {

struct SiteOptions {
  int columns = 64, rows = 48;
  double spacing_m = 4.0;
  bool land = true;         ///< a land block in the north-east and a breakwater
  double choppiness = 0.0;
};

/// 64 x 48 cells of 4 m: 12 m deep in the south shoaling northwards; with `land`, a land block in
/// the north-east corner (cells i >= 44, j >= 34) and a rubble breakwater (porosity 0.4) along
/// row 24 from i = 8 to 30. Waves come from the south (source line y = 0), blend 8..48 m inland,
/// the other edges fade over 24 m.
inline std::shared_ptr<runtime::HarbourSite> make_site(const SiteOptions& o = {}) {
  GridGeometry geometry;
  geometry.columns = o.columns;
  geometry.rows = o.rows;
  geometry.spacing_m = o.spacing_m;
  geometry.origin_x_m = 386128.0;  // projected coordinates: the site frame must not care
  geometry.origin_y_m = 4306447.0;
  auto site = std::make_shared<runtime::HarbourSite>();
  site->harbour = HarbourGrid::open_water(geometry, 12.f);
  for (int j = 0; j < o.rows; ++j)
    for (int i = 0; i < o.columns; ++i) {
      float depth = 12.f - 9.f * float(j) / float(o.rows - 1);
      bool land = false;
      if (o.land && i >= o.columns * 11 / 16 && j >= o.rows * 34 / 48) {
        depth = -2.f - 0.05f * float(i);
        land = true;
      }
      site->harbour.still_water_depth_m(i, j) = depth;
      site->harbour.land(i, j) = land ? 1 : 0;
      if (o.land && j == o.rows / 2 && i >= o.columns / 8 && i <= o.columns * 30 / 64) site->harbour.porosity(i, j) = 0.4f;
    }
  site->width_m = o.columns * o.spacing_m;
  site->height_m = o.rows * o.spacing_m;
  site->source_axis = 1;
  site->inward_sign = 1.0;
  site->source_line_m = 0.0;
  site->blend_start_m = 8.0;
  site->blend_width_m = 40.0;
  site->edge_fade_m = 24.0;
  site->choppiness = o.choppiness;
  site->frame_interval_s = 0.5;  // the keyframes carry rates: the Hermite in time (surface_snapshot.hpp)
  return site;
}

/// The analytic harbour field of keyframe `which` (0 or 1) at a cell centre (m).
inline double analytic_eta_m(int which, double x, double y) {
  return which == 0 ? 0.8 * std::sin(2 * std::numbers::pi * (x / 61.0 + y / 37.0))
                    : 0.5 * std::cos(2 * std::numbers::pi * (x / 43.0 - y / 29.0)) + 0.1;
}

/// Its d eta / dt (m/s), any smooth field: the GPU and the CPU must join the keyframes alike.
inline double analytic_eta_rate_m_s(int which, double x, double y) {
  return which == 0 ? 0.6 * std::cos(2 * std::numbers::pi * (x / 53.0 + y / 41.0))
                    : -0.4 * std::sin(2 * std::numbers::pi * (x / 47.0 - y / 33.0));
}

inline std::shared_ptr<runtime::HarbourKeyframe> make_harbour_keyframe(const runtime::HarbourSite& site, int which,
                                                                       std::uint64_t serial) {
  auto keyframe = std::make_shared<runtime::HarbourKeyframe>();
  keyframe->serial = serial;
  const GridGeometry& g = site.harbour.geometry;
  keyframe->surface_elevation_m = Raster<float>(g.columns, g.rows);
  keyframe->breaking = Raster<float>(g.columns, g.rows, 0.f);
  keyframe->surface_elevation_rate_m_s = Raster<float>(g.columns, g.rows);
  for (int j = 0; j < g.rows; ++j)
    for (int i = 0; i < g.columns; ++i) {
      const double x = (i + 0.5) * g.spacing_m, y = (j + 0.5) * g.spacing_m;
      keyframe->surface_elevation_m(i, j) = float(analytic_eta_m(which, x, y));
      keyframe->surface_elevation_rate_m_s(i, j) = float(analytic_eta_rate_m_s(which, x, y));
    }
  return keyframe;
}

/// Deep water of Beaufort force `force`, one or more cascades, synthesised at two times.
struct DeepPair {
  std::shared_ptr<runtime::DeepWaterKeyframe> from, to;
};
inline DeepPair make_deep_pair(int force, std::vector<double> tile_lengths_m, int grid_size, double t0_s, double t1_s,
                               std::uint64_t serial) {
  ocean::DeepWaterSpecification specification;
  specification.spectrum = ocean::beaufort_preset(force, 0.6).spectrum;
  specification.tile_lengths_m = std::move(tile_lengths_m);
  specification.grid_size = grid_size;
  specification.seed = 7;
  ocean::DeepWaterField field(specification);
  DeepPair pair;
  for (auto* keyframe : {&pair.from, &pair.to}) {
    const double t = keyframe == &pair.from ? t0_s : t1_s;
    field.synthesise(t);
    *keyframe = std::make_shared<runtime::DeepWaterKeyframe>();
    (*keyframe)->serial = serial++;
    (*keyframe)->display_time_s = t;
    for (int c = 0; c < field.cascade_count(); ++c) (*keyframe)->cascades.push_back(field.frame(c));
  }
  return pair;
}

}  // namespace nearshore::test
