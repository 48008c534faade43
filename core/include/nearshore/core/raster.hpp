#pragma once
// Raster<T>: a regular 2-D grid of values on the projected metric frame of a harbour, and
// GridGeometry: where that grid lies. Convention (docs/formats.md): column i runs east (+x),
// row j runs NORTH (+y), row 0 is the southern edge; cell (i, j) has its centre at
//   x = origin_x_m + (i + 0.5) * spacing_m,  y = origin_y_m + (j + 0.5) * spacing_m.
// GeoTIFF writers flip rows (GeoTIFF stores the northern row first).
#include <cassert>
#include <cstddef>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace nearshore {

struct GridGeometry {
  int columns = 0;            ///< cells along x (east)
  int rows = 0;               ///< cells along y (north)
  double spacing_m = 1.0;     ///< cell size, metres, the same along x and y
  double origin_x_m = 0.0;    ///< x of the south-west corner of cell (0, 0), metres
  double origin_y_m = 0.0;    ///< y of the south-west corner of cell (0, 0), metres
  std::string crs_wkt;        ///< the projected CRS of x and y (OGC WKT), empty for a laboratory frame
  nlohmann::json projection;  ///< how to get lat/lon (e.g. {"kind":"utm","zone":10,"north":true}); docs/formats.md

  double cell_centre_x_m(int column) const { return origin_x_m + (column + 0.5) * spacing_m; }
  double cell_centre_y_m(int row) const { return origin_y_m + (row + 0.5) * spacing_m; }
  double width_m() const { return columns * spacing_m; }
  double height_m() const { return rows * spacing_m; }
  std::size_t cell_count() const { return static_cast<std::size_t>(columns) * static_cast<std::size_t>(rows); }
};

void to_json(nlohmann::json& out, const GridGeometry& geometry);
void from_json(const nlohmann::json& in, GridGeometry& geometry);

template <class T>
class Raster {
 public:
  Raster() = default;
  Raster(int columns, int rows, T fill = T{})
      : columns_(columns), rows_(rows), values_(static_cast<std::size_t>(columns) * rows, fill) {}

  int columns() const { return columns_; }
  int rows() const { return rows_; }
  std::size_t size() const { return values_.size(); }
  bool empty() const { return values_.empty(); }
  T& operator()(int column, int row) {
    assert(column >= 0 && column < columns_ && row >= 0 && row < rows_);
    return values_[static_cast<std::size_t>(row) * columns_ + column];
  }
  const T& operator()(int column, int row) const {
    assert(column >= 0 && column < columns_ && row >= 0 && row < rows_);
    return values_[static_cast<std::size_t>(row) * columns_ + column];
  }
  T* data() { return values_.data(); }
  const T* data() const { return values_.data(); }
  std::vector<T>& values() { return values_; }
  const std::vector<T>& values() const { return values_; }

 private:
  int columns_ = 0, rows_ = 0;
  std::vector<T> values_;
};

}  // namespace nearshore
