// The only translation unit that includes CGAL (see natural_neighbour.hpp).
#include "nearshore/bathymetry/natural_neighbour.hpp"

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/natural_neighbor_coordinates_2.h>
#include <CGAL/property_map.h>
#include <CGAL/spatial_sort.h>
#include <CGAL/Spatial_sort_traits_adapter_2.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <cmath>
#include <limits>
#include <mutex>
#include <vector>

namespace nearshore::bathymetry {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
struct VertexData {
  double depth_m = 0.0;
  std::size_t owner = 0;  // index of the input point this vertex came from
};
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<VertexData, Kernel>;
using DataStructure = CGAL::Triangulation_data_structure_2<VertexBase>;
using Delaunay = CGAL::Delaunay_triangulation_2<Kernel, DataStructure>;
using Vertex = Delaunay::Vertex_handle;
using Face = Delaunay::Face_handle;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Sibson interpolant sum_i lambda_i(p) z_i / sum_i lambda_i(p) (Sibson 1981 eq. 1), starting the
// point location at `hint` (the previous cell's face: neighbouring queries walk a few faces only).
double sibson(const Delaunay& triangulation, const Kernel::Point_2& p, Face& hint) {
  if (triangulation.dimension() < 2) return kNaN;
  thread_local std::vector<std::pair<Vertex, double>> coordinates;
  coordinates.clear();
  const auto result = CGAL::natural_neighbor_coordinates_2(
      triangulation, p, std::back_inserter(coordinates), CGAL::Identity<std::pair<Vertex, double>>(), hint);
  if (!result.third) return kNaN;
  double weighted = 0.0;
  for (const auto& [vertex, lambda] : coordinates) weighted += lambda * vertex->info().depth_m;
  if (!coordinates.empty()) hint = coordinates.front().first->face();
  return weighted / result.second;
}

}  // namespace

struct NaturalNeighbourSurface::Triangulation {
  Delaunay delaunay;
  std::vector<ScatteredDepth> points;
  std::vector<Vertex> vertex_of_point;  // null where the point duplicated an earlier one
};

NaturalNeighbourSurface::NaturalNeighbourSurface(std::span<const ScatteredDepth> points)
    : triangulation_(std::make_unique<Triangulation>()) {
  auto& t = *triangulation_;
  t.points.assign(points.begin(), points.end());
  t.vertex_of_point.assign(points.size(), Vertex());
  // Spatially sorted insertion (CGAL's Hilbert sort) keeps each insertion's walk short.
  using Indexed = std::pair<Kernel::Point_2, std::size_t>;
  std::vector<Indexed> sorted;
  sorted.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) sorted.push_back({{points[i].x_m, points[i].y_m}, i});
  CGAL::spatial_sort(sorted.begin(), sorted.end(),
                     CGAL::Spatial_sort_traits_adapter_2<Kernel, CGAL::First_of_pair_property_map<Indexed>>());
  Face hint;
  for (const auto& [point, index] : sorted) {
    const std::size_t before = t.delaunay.number_of_vertices();
    Vertex vertex = t.delaunay.insert(point, hint);
    hint = vertex->face();
    const bool is_new = t.delaunay.number_of_vertices() > before;
    // Coincident points: the one listed first in the input owns the vertex and its depth.
    if (is_new || index < vertex->info().owner) {
      if (!is_new) t.vertex_of_point[vertex->info().owner] = Vertex();
      vertex->info() = {points[index].depth_m, index};
      t.vertex_of_point[index] = vertex;
    }
  }
}

NaturalNeighbourSurface::~NaturalNeighbourSurface() = default;
NaturalNeighbourSurface::NaturalNeighbourSurface(NaturalNeighbourSurface&&) noexcept = default;
NaturalNeighbourSurface& NaturalNeighbourSurface::operator=(NaturalNeighbourSurface&&) noexcept = default;

std::size_t NaturalNeighbourSurface::vertex_count() const { return triangulation_->delaunay.number_of_vertices(); }

double NaturalNeighbourSurface::depth_at(double x_m, double y_m) const {
  Face hint;
  return sibson(triangulation_->delaunay, {x_m, y_m}, hint);
}

Raster<float> NaturalNeighbourSurface::sample(const GridGeometry& geometry, const Raster<std::uint8_t>* skip,
                                              ProgressBar* progress) const {
  Raster<float> depth(geometry.columns, geometry.rows, std::numeric_limits<float>::quiet_NaN());
  const Delaunay& delaunay = triangulation_->delaunay;
  std::atomic<int> rows_done{0};
  std::mutex progress_mutex;
  // Queries only read the triangulation (locate and conflict search are const and keep no shared
  // state), so rows can be interpolated concurrently.
  tbb::parallel_for(tbb::blocked_range<int>(0, geometry.rows, 4), [&](const tbb::blocked_range<int>& rows) {
    Face hint;
    for (int row = rows.begin(); row != rows.end(); ++row) {
      const double y = geometry.cell_centre_y_m(row);
      for (int column = 0; column < geometry.columns; ++column)
        if (!skip || !(*skip)(column, row))
          depth(column, row) = static_cast<float>(sibson(delaunay, {geometry.cell_centre_x_m(column), y}, hint));
      const int done = ++rows_done;
      if (progress && progress_mutex.try_lock()) {
        progress->update(done);
        progress_mutex.unlock();
      }
    }
  });
  return depth;
}

double NaturalNeighbourSurface::leave_one_out(std::size_t index) {
  auto& t = *triangulation_;
  if (index >= t.points.size() || t.vertex_of_point[index] == Vertex()) return kNaN;
  const ScatteredDepth& point = t.points[index];
  t.delaunay.remove(t.vertex_of_point[index]);
  Face hint;
  const double estimate = sibson(t.delaunay, {point.x_m, point.y_m}, hint);
  Vertex vertex = t.delaunay.insert({point.x_m, point.y_m});
  vertex->info() = {point.depth_m, index};
  t.vertex_of_point[index] = vertex;
  return estimate;
}

}  // namespace nearshore::bathymetry
