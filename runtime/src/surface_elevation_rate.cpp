// The harbour keyframes' time interpolation (surface_snapshot.hpp): the cubic Hermite basis and
// each keyframe's d eta / dt from the bake's mass equation.
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

  // G along one axis: the centred difference of the cell averages (one-sided at the grid's edge).
  // stride: 1 along x, columns along y; count, position: the axis's length and a cell's index on it.
  auto smoothed_divergence = [&](const Raster<float>& flux, double spacing_m, bool along_x) {
    std::vector<double> g(cells, 0.0);
    const std::ptrdiff_t stride = along_x ? 1 : columns;
    const int count = along_x ? columns : rows;
    for (int r = 0; r < rows; ++r)
      for (int c = 0; c < columns; ++c) {
        const std::size_t i = static_cast<std::size_t>(r) * columns + c;
        if (!water[i] || count < 2) continue;
        const int position = along_x ? c : r;
        const bool has_before = position > 0, has_after = position + 1 < count;
        // A land or wall neighbour holds no flux: its average is 0, as the solver's wall face is.
        const double before = has_before ? (water[i - stride] ? flux.values()[i - stride] : 0.0) : flux.values()[i];
        const double after = has_after ? (water[i + stride] ? flux.values()[i + stride] : 0.0) : flux.values()[i];
        g[i] = (after - before) / ((has_before && has_after ? 2.0 : 1.0) * spacing_m);
      }
    // D = G - (G_{i-1} - 2 G_i + G_{i+1}) / 4 where both neighbours are water.
    std::vector<double> d = g;
    for (int r = 0; r < rows; ++r)
      for (int c = 0; c < columns; ++c) {
        const std::size_t i = static_cast<std::size_t>(r) * columns + c;
        const int position = along_x ? c : r;
        if (!water[i] || position == 0 || position + 1 == count || !water[i - stride] || !water[i + stride]) continue;
        d[i] = g[i] - 0.25 * (g[i - stride] - 2.0 * g[i] + g[i + stride]);
      }
    return d;
  };
  const std::vector<double> dp_dx = smoothed_divergence(flux_x_m2_s, grid.geometry.spacing_x_m(), true);
  const std::vector<double> dq_dy = smoothed_divergence(flux_y_m2_s, grid.geometry.spacing_y_m(), false);
  Raster<float> rate(columns, rows, 0.0f);
  for (std::size_t i = 0; i < cells; ++i)
    if (water[i]) rate.values()[i] = static_cast<float>(-(dp_dx[i] + dq_dy[i]) / porosity(i));
  return rate;
}

}  // namespace nearshore::runtime
