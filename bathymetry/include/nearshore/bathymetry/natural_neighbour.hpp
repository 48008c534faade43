#pragma once
// NaturalNeighbourSurface: Sibson natural-neighbour interpolation (Sibson 1981) of scattered depths
// over their Delaunay triangulation. The interpolant is continuous, equals the data at the data
// points, and reproduces any linear function exactly (linear precision), so on a plane it is exact
// and on a smooth surface its error falls as O(h^2) with the data spacing h.
//
// Constraints (coastline at depth 0, contours at their value, depth-area boundaries) enter as
// vertices densified along each line to at most the grid spacing, so the triangulation conforms to
// them at the grid's resolution: CGAL's Sibson coordinates need a true Delaunay triangulation, which
// a constrained one is not.
//
// CGAL is confined to natural_neighbour.cpp (it compiles slowly); this header is plain C++.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>

#include "nearshore/core/progress.hpp"
#include "nearshore/core/raster.hpp"

namespace nearshore::bathymetry {

struct ScatteredDepth {
  double x_m = 0.0, y_m = 0.0;  ///< projected position, metres
  double depth_m = 0.0;         ///< value to interpolate (depth positive down)
};

class NaturalNeighbourSurface {
 public:
  /// Triangulates the points. Where two points coincide the FIRST one is kept (so callers list
  /// their data in priority order).
  explicit NaturalNeighbourSurface(std::span<const ScatteredDepth> points);
  ~NaturalNeighbourSurface();
  NaturalNeighbourSurface(NaturalNeighbourSurface&&) noexcept;
  NaturalNeighbourSurface& operator=(NaturalNeighbourSurface&&) noexcept;

  std::size_t vertex_count() const;
  /// The Sibson interpolant at (x, y); NaN outside the convex hull of the data.
  double depth_at(double x_m, double y_m) const;
  /// depth_at every cell centre of `geometry`, rows in parallel (oneTBB). NaN outside the hull
  /// and where `skip` (if given, same size) is non-zero. `progress`, if given, advances in rows.
  Raster<float> sample(const GridGeometry& geometry, const Raster<std::uint8_t>* skip = nullptr,
                       ProgressBar* progress = nullptr) const;
  /// Leave-one-out: removes input point `index` from the triangulation, interpolates at its
  /// place from the others, puts it back, and returns the interpolated value (NaN if it was a
  /// duplicate that was never inserted or falls outside the hull of the others).
  double leave_one_out(std::size_t index);

 private:
  struct Triangulation;
  std::unique_ptr<Triangulation> triangulation_;
};

}  // namespace nearshore::bathymetry
