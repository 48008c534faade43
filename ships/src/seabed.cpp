#include "nearshore/ships/seabed.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "nearshore/core/error.hpp"

namespace nearshore::ships {

Seabed::Seabed(std::shared_ptr<const runtime::HarbourSite> site, HarbourObstacleOptions obstacles) : site_(std::move(site)) {
  if (!site_ || site_->harbour.still_water_depth_m.empty())
    throw Error("Seabed", "the harbour site has no depth raster", "give the site of a sequence (read_harbour_site)");
  obstacles_ = std::make_shared<const HarbourObstacles>(site_->harbour, obstacles);
}

Seabed Seabed::flat(double depth_m) {
  Seabed seabed;
  seabed.flat_depth_m_ = depth_m;
  return seabed;
}

double Seabed::depth_m(double x_m, double y_m) const {
  if (!site_) return flat_depth_m_;
  // A NaN position has no cell: casting it to an index is undefined (issue 44: an initial speed of
  // 1e308 m/s made the hull's points NaN and this lookup read far outside the raster).
  if (std::isnan(x_m) || std::isnan(y_m)) return std::numeric_limits<double>::quiet_NaN();
  const Raster<float>& d = site_->harbour.still_water_depth_m;
  const double dx = site_->harbour.geometry.spacing_x_m(), dy = site_->harbour.geometry.spacing_y_m();
  const int columns = d.columns(), rows = d.rows();
  // surface_sampler.hpp formula 1: cell centres, clamp to edge.
  const double u = std::clamp(x_m / dx - 0.5, 0.0, static_cast<double>(columns - 1));
  const double v = std::clamp(y_m / dy - 0.5, 0.0, static_cast<double>(rows - 1));
  const int i0 = std::min(static_cast<int>(u), std::max(columns - 2, 0)), j0 = std::min(static_cast<int>(v), std::max(rows - 2, 0));
  const int i1 = std::min(i0 + 1, columns - 1), j1 = std::min(j0 + 1, rows - 1);
  const double a = columns > 1 ? u - i0 : 0.0, b = rows > 1 ? v - j0 : 0.0;
  return (1 - b) * ((1 - a) * d(i0, j0) + a * d(i1, j0)) + b * ((1 - a) * d(i0, j1) + a * d(i1, j1));
}

bool Seabed::covers(double x_m, double y_m) const {
  if (!site_) return true;
  return x_m >= 0.0 && y_m >= 0.0 && x_m <= site_->harbour.geometry.width_m() && y_m <= site_->harbour.geometry.height_m();
}

}  // namespace nearshore::ships
