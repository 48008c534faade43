// The harbour keyframes' time interpolation (surface_snapshot.hpp): the cubic Hermite basis and
// each keyframe's d eta / dt from the bake's mass equation.
#include <algorithm>
#include <cmath>
#include <cstddef>

#include <fmt/core.h>

#include "nearshore/core/error.hpp"
#include "nearshore/runtime/surface_snapshot.hpp"

namespace nearshore::runtime {

HermiteWeights hermite_weights(double f) {
  const double f2 = f * f, f3 = f2 * f;
  HermiteWeights h;
  h.from = 2.0 * f3 - 3.0 * f2 + 1.0;
  h.from_rate = f3 - 2.0 * f2 + f;
  h.to = -2.0 * f3 + 3.0 * f2;
  h.to_rate = f3 - f2;
  h.d_from = 6.0 * f2 - 6.0 * f;
  h.d_from_rate = 3.0 * f2 - 4.0 * f + 1.0;
  h.d_to = -6.0 * f2 + 6.0 * f;
  h.d_to_rate = 3.0 * f2 - 2.0 * f;
  return h;
}

bool harbour_joined_by_hermite(const SurfaceSnapshot& snapshot) {
  if (!snapshot.site || !snapshot.harbour_from || !(snapshot.site->frame_interval_s > 0.0) || !std::isfinite(snapshot.site->frame_interval_s))
    return false;
  const HarbourKeyframe& from = *snapshot.harbour_from;
  const HarbourKeyframe& to = snapshot.harbour_to ? *snapshot.harbour_to : from;
  return from.surface_elevation_rate_m_s.size() == from.surface_elevation_m.size() &&
         to.surface_elevation_rate_m_s.size() == to.surface_elevation_m.size();
}

void shown_harbour_elevation(const SurfaceSnapshot& snapshot, float* elevation_m) {
  if (!snapshot.site) return;
  const std::size_t cells = snapshot.site->harbour.geometry.cell_count();
  if (!snapshot.harbour_from) {
    std::fill(elevation_m, elevation_m + cells, 0.f);
    return;
  }
  const HarbourKeyframe& from = *snapshot.harbour_from;
  const HarbourKeyframe& to = snapshot.harbour_to ? *snapshot.harbour_to : from;
  if (harbour_joined_by_hermite(snapshot) && from.surface_elevation_m.size() == cells && to.surface_elevation_m.size() == cells) {
    const HermiteWeights h = hermite_weights(snapshot.harbour_fraction);
    const double T = snapshot.site->frame_interval_s;
    for (std::size_t i = 0; i < cells; ++i)
      elevation_m[i] = static_cast<float>(h.from * from.surface_elevation_m.values()[i] + h.from_rate * T * from.surface_elevation_rate_m_s.values()[i] +
                                          h.to * to.surface_elevation_m.values()[i] + h.to_rate * T * to.surface_elevation_rate_m_s.values()[i]);
    return;
  }
  const float linear = static_cast<float>(snapshot.harbour_fraction);
  for (std::size_t i = 0; i < cells; ++i)
    elevation_m[i] = (1.f - linear) * from.surface_elevation_m.values()[i] + linear * to.surface_elevation_m.values()[i];
}

Raster<float> surface_elevation_rate(const HarbourGrid& grid, const Raster<float>& flux_x_m2_s, const Raster<float>& flux_y_m2_s) {
  const int columns = grid.geometry.columns, rows = grid.geometry.rows;
  for (const Raster<float>* flux : {&flux_x_m2_s, &flux_y_m2_s})
    if (flux->columns() != columns || flux->rows() != rows)
      throw Error("surface_elevation_rate",
                  fmt::format("a {} x {} flux raster on a {} x {} harbour grid", flux->columns(), flux->rows(), columns, rows),
                  "give the keyframe's own fluxes and its sequence's grid");
  const std::size_t cells = static_cast<std::size_t>(columns) * rows;
  const bool has_land = grid.land.columns() == columns && grid.land.rows() == rows;
  const bool has_porosity = grid.porosity.columns() == columns && grid.porosity.rows() == rows;
  auto porosity = [&](std::size_t i) { return has_porosity ? grid.porosity.values()[i] : 1.0f; };
  // Water that carries flux: not land, not a wall.
  std::vector<unsigned char> water(cells);
  for (std::size_t i = 0; i < cells; ++i) water[i] = (!has_land || grid.land.values()[i] == kWaterCell) && porosity(i) > 0.0f;

  // One pass, no temporaries (a 1024 x 1024 keyframe is decoded 15 times a second). Along an axis
  // (stride 1 for x, columns for y; `position` the cell's index on it, `count` its length):
  //   G_j = (A_{j+1} - A_{j-1}) / (2 dx), one-sided at the grid's edge, a land or wall neighbour's
  //         average 0 (it holds no flux, as the solver's wall face);
  //   D_i = G_i - (G_{i-1} - 2 G_i + G_{i+1}) / 4 where both neighbours are water, else G_i.
  // Where the four neighbours are water inside the grid this is the five-point
  //   D_i = (6 (A_{i+1} - A_{i-1}) - (A_{i+2} - A_{i-2})) / (8 dx).
  auto divergence = [&](const float* a, std::size_t i, int position, int count, std::ptrdiff_t stride, double spacing_m) {
    auto g_at = [&](std::size_t j, int at) {
      const bool has_before = at > 0, has_after = at + 1 < count;
      const double before = has_before ? (water[j - stride] ? a[j - stride] : 0.0) : a[j];
      const double after = has_after ? (water[j + stride] ? a[j + stride] : 0.0) : a[j];
      return (after - before) / ((has_before && has_after ? 2.0 : 1.0) * spacing_m);
    };
    if (count < 2) return 0.0;
    if (position >= 2 && position + 2 < count && water[i - 2 * stride] && water[i - stride] && water[i + stride] && water[i + 2 * stride])
      return (6.0 * (static_cast<double>(a[i + stride]) - a[i - stride]) - (static_cast<double>(a[i + 2 * stride]) - a[i - 2 * stride])) /
             (8.0 * spacing_m);
    const double g = g_at(i, position);
    if (position == 0 || position + 1 == count || !water[i - stride] || !water[i + stride]) return g;
    return g - 0.25 * (g_at(i - stride, position - 1) - 2.0 * g + g_at(i + stride, position + 1));
  };
  Raster<float> rate(columns, rows, 0.0f);
  const float* p = flux_x_m2_s.data();
  const float* q = flux_y_m2_s.data();
  const double dx = grid.geometry.spacing_x_m(), dy = grid.geometry.spacing_y_m();
  // Open water two cells from any land, wall and edge (most of a harbour) takes the five-point
  // form along both axes in a tight loop in float (within a float's rounding of `divergence`,
  // which works in double: the rate is stored as a float), vectorised; the rest goes cell by cell.
  const double per_8dx = 1.0 / (8.0 * dx), per_8dy = 1.0 / (8.0 * dy);
  std::vector<unsigned char> open(cells, 0);
  for (int r = 2; r + 2 < rows; ++r) {
    const std::size_t row = static_cast<std::size_t>(r) * columns;
    const std::size_t up = static_cast<std::size_t>(columns), up2 = 2 * up;
    for (int c = 2; c + 2 < columns; ++c) {
      const std::size_t i = row + c;
      open[i] = water[i] & water[i - 1] & water[i + 1] & water[i - 2] & water[i + 2] & water[i - up] & water[i + up] &
                water[i - up2] & water[i + up2];
    }
  }
  for (int r = 0; r < rows; ++r) {
    const std::size_t row = static_cast<std::size_t>(r) * columns;
    float* out = rate.values().data() + row;
    if (r >= 2 && r + 2 < rows) {
      const std::ptrdiff_t up = columns;
      const float* __restrict pr = p + row;
      const float* __restrict qr = q + row;
      float* __restrict o = out;
      // In float, packed (4 or 8 cells a instruction): the rate is stored as a float anyway.
      const float fx = static_cast<float>(per_8dx), fy = static_cast<float>(per_8dy);
      for (int c = 2; c + 2 < columns; ++c)
        o[c] = -((6.0f * (pr[c + 1] - pr[c - 1]) - (pr[c + 2] - pr[c - 2])) * fx +
                 (6.0f * (qr[c + up] - qr[c - up]) - (qr[c + 2 * up] - qr[c - 2 * up])) * fy);
      if (has_porosity) {  // walls (n = 0) are not open water: the pass below writes them
        const float* __restrict n = grid.porosity.values().data() + row;
        for (int c = 2; c + 2 < columns; ++c) o[c] /= n[c] > 0.0f ? n[c] : 1.0f;
      }
    }
    for (int c = 0; c < columns; ++c) {
      const std::size_t i = row + c;
      if (open[i]) continue;
      if (!water[i]) {
        out[c] = 0.0f;
        continue;
      }
      const double div = divergence(p, i, c, columns, 1, dx) + divergence(q, i, r, rows, columns, dy);
      out[c] = static_cast<float>(-div / porosity(i));
    }
  }
  return rate;
}

}  // namespace nearshore::runtime
