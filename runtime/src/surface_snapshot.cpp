#include "nearshore/runtime/surface_snapshot.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace nearshore::runtime {

namespace {
// sin^2 ramp from 0 at s = 0 to 1 at s = width (the bake's blending record's rule).
double sin2_ramp(double s, double width) {
  if (width <= 0.0) return s > 0.0 ? 1.0 : 0.0;
  const double u = std::clamp(s / width, 0.0, 1.0);
  const double r = std::sin(0.5 * std::numbers::pi * u);
  return r * r;
}
}  // namespace

double harbour_weight(const HarbourSite& site, double x_m, double y_m) {
  if (x_m < 0.0 || y_m < 0.0 || x_m > site.width_m || y_m > site.height_m) return 0.0;
  const double along = site.source_axis == 0 ? x_m : y_m;
  // Distance inland of the source line along the maker's inward normal.
  const double inland = site.inward_sign * (along - site.source_line_m);
  double weight = sin2_ramp(inland - site.blend_start_m, site.blend_width_m);
  // The three other edges fade over edge_fade_m (the source side fades by the record above).
  const double distances[4] = {x_m, site.width_m - x_m, y_m, site.height_m - y_m};  // west, east, south, north
  const int source_edge = site.source_axis == 0 ? (site.inward_sign > 0 ? 0 : 1) : (site.inward_sign > 0 ? 2 : 3);
  for (int edge = 0; edge < 4; ++edge)
    if (edge != source_edge) weight *= sin2_ramp(distances[edge], site.edge_fade_m);
  return weight;
}

}  // namespace nearshore::runtime
