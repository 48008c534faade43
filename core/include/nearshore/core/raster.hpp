#pragma once
// Raster<T>: a regular 2-D grid of values on the projected metric frame of a harbour, and
// GridGeometry: where that grid lies. Convention (docs/formats.md): column i runs east (+x),
// row j runs NORTH (+y), row 0 is the southern edge; cell (i, j) has its centre at
//   x = origin_x_m + (i + 0.5) * spacing_x_m(),  y = origin_y_m + (j + 0.5) * spacing_y_m().
// Cells are square unless set_spacing gives two sizes (rectangular cells, dx != dy, as FUNWAVE-TVD
// and MIKE 21 BW allow: a long flume or a harbour entrance resolved finer along the waves).
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
  /// Cell size along x (east), metres; for square cells (the default) also the size along y. Code
  /// written for square cells may keep reading it as "the" spacing where square_cells() holds;
  /// everything that differentiates, interpolates or sums over area uses spacing_x_m() / spacing_y_m().
  double spacing_m = 1.0;
  double origin_x_m = 0.0;    ///< x of the south-west corner of cell (0, 0), metres
  double origin_y_m = 0.0;    ///< y of the south-west corner of cell (0, 0), metres
  std::string crs_wkt;        ///< the projected CRS of x and y (OGC WKT), empty for a laboratory frame
  nlohmann::json projection;  ///< how to get lat/lon (e.g. {"kind":"utm","zone":10,"north":true}); docs/formats.md
  /// Cell size along y (north), metres, where it differs from spacing_m; 0 = square cells. Read it
  /// through spacing_y_m(), set it through set_spacing(). Last, so that positional initialisers
  /// written for square grids ({columns, rows, spacing, origin x, origin y, ...}) keep their meaning.
  double rectangular_spacing_y_m = 0.0;

  double spacing_x_m() const { return spacing_m; }  ///< dx, metres
  double spacing_y_m() const { return rectangular_spacing_y_m > 0.0 ? rectangular_spacing_y_m : spacing_m; }  ///< dy, metres
  bool square_cells() const { return spacing_y_m() == spacing_m; }
  double smaller_spacing_m() const { return spacing_m < spacing_y_m() ? spacing_m : spacing_y_m(); }  ///< min(dx, dy)
  double cell_area_m2() const { return spacing_m * spacing_y_m(); }
  /// Sets dx and dy (metres); equal sizes give square cells (rectangular_spacing_y_m = 0).
  void set_spacing(double spacing_x, double spacing_y) {
    spacing_m = spacing_x;
    rectangular_spacing_y_m = spacing_y == spacing_x ? 0.0 : spacing_y;
  }
  double cell_centre_x_m(int column) const { return origin_x_m + (column + 0.5) * spacing_m; }
  double cell_centre_y_m(int row) const { return origin_y_m + (row + 0.5) * spacing_y_m(); }
  double width_m() const { return columns * spacing_m; }
  double height_m() const { return rows * spacing_y_m(); }
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
