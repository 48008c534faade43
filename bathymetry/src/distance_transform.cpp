#include "nearshore/bathymetry/distance_transform.hpp"

#include <tbb/parallel_for.h>

#include <cmath>
#include <limits>
#include <vector>

namespace nearshore::bathymetry {
namespace {

constexpr double kFar = 1e30;  // "no seed" in squared cell units (F&H use +inf; finite keeps the algebra clean)

// 1-D squared distance transform of f over n samples (F&H 2012, algorithm "DT(f)"): d(q) =
// min_p ((q - p)^2 + f(p)), and arg(q) the minimising p. v/z hold the lower envelope of parabolas.
void squared_distance_1d(const double* f, int n, double* d, int* arg, std::vector<int>& v, std::vector<double>& z) {
  v.assign(n, 0);
  z.assign(n + 1, 0.0);
  int k = 0;
  v[0] = 0;
  z[0] = -INFINITY;
  z[1] = INFINITY;
  auto intersection = [&](int q, int p) { return ((f[q] + double(q) * q) - (f[p] + double(p) * p)) / (2.0 * q - 2.0 * p); };
  for (int q = 1; q < n; ++q) {
    double s = intersection(q, v[k]);
    while (s <= z[k]) s = intersection(q, v[--k]);  // z[0] = -inf stops this at k = 0
    ++k;
    v[k] = q;
    z[k] = s;
    z[k + 1] = INFINITY;
  }
  k = 0;
  for (int q = 0; q < n; ++q) {
    while (z[k + 1] < q) ++k;
    d[q] = (double(q) - v[k]) * (double(q) - v[k]) + f[v[k]];
    arg[q] = v[k];
  }
}

}  // namespace

NearestSeed nearest_seed_transform(const Raster<std::uint8_t>& seed, double spacing_m) {
  const int columns = seed.columns(), rows = seed.rows();
  // Pass 1, down each column: squared distance (in cells) to the nearest seed of that column.
  Raster<double> column_distance(columns, rows);
  Raster<std::int32_t> column_seed_row(columns, rows, -1);
  tbb::parallel_for(0, columns, [&](int column) {
    std::vector<double> f(rows), d(rows);
    std::vector<int> arg(rows), v;
    std::vector<double> z;
    for (int row = 0; row < rows; ++row) f[row] = seed(column, row) ? 0.0 : kFar;
    squared_distance_1d(f.data(), rows, d.data(), arg.data(), v, z);
    for (int row = 0; row < rows; ++row) {
      column_distance(column, row) = d[row];
      column_seed_row(column, row) = d[row] < kFar ? arg[row] : -1;
    }
  });
  // Pass 2, along each row over the column results: the exact 2-D squared distance.
  NearestSeed out{Raster<float>(columns, rows), Raster<std::int32_t>(columns, rows, -1),
                  Raster<std::int32_t>(columns, rows, -1)};
  tbb::parallel_for(0, rows, [&](int row) {
    std::vector<double> d(columns);
    std::vector<int> arg(columns), v;
    std::vector<double> z;
    squared_distance_1d(&column_distance(0, row), columns, d.data(), arg.data(), v, z);
    for (int column = 0; column < columns; ++column) {
      const bool found = d[column] < kFar / 2;
      out.distance_m(column, row) = found ? static_cast<float>(std::sqrt(d[column]) * spacing_m)
                                          : std::numeric_limits<float>::infinity();
      out.nearest_column(column, row) = found ? arg[column] : -1;
      out.nearest_row(column, row) = found ? column_seed_row(arg[column], row) : -1;
    }
  });
  return out;
}

Raster<float> signed_coast_distance(const Raster<std::uint8_t>& land, double spacing_m) {
  Raster<std::uint8_t> water(land.columns(), land.rows());
  for (std::size_t i = 0; i < land.size(); ++i) water.values()[i] = land.values()[i] ? 0 : 1;
  const Raster<float> to_land = nearest_seed_transform(land, spacing_m).distance_m;
  const Raster<float> to_water = nearest_seed_transform(water, spacing_m).distance_m;
  Raster<float> signed_distance(land.columns(), land.rows());
  const float half_cell = static_cast<float>(0.5 * spacing_m);
  for (std::size_t i = 0; i < land.size(); ++i)
    signed_distance.values()[i] = land.values()[i] ? -(to_water.values()[i] - half_cell) : to_land.values()[i] - half_cell;
  return signed_distance;
}

}  // namespace nearshore::bathymetry
