// The surface roller (Schaffer, Madsen & Deigaard 1993; Madsen, Sorensen & Schaffer 1997, Part I):
// roller geometry from the surface, the roller's age, its momentum flux and the force on the faces.
// docs/solver.md, "Breaking: the surface roller", derives each step.
#include "surface_roller.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "nearshore/ocean/wave_component.hpp"

namespace nearshore::boussinesq::detail {

namespace {
// A roller thinner than this share of the depth is no roller (the tangent line touches the
// surface within round-off).
constexpr double kMinimumThickness_m = 1e-9;
// delta / h is held below this: the momentum flux delta (c - u)^2 / (1 - delta/h) grows without
// bound as the roller fills the water column, which the two-layer picture of Schaffer et al. (1993)
// does not allow. A guard of the closure's range, not a fitted constant (docs/solver.md).
constexpr double kMaximumDepthShare = 0.5;
}  // namespace

SurfaceRoller::SurfaceRoller(const RollerGrid& grid, const RollerConstants& constants) : grid_(grid), k_(constants) {
  const std::size_t cells = static_cast<std::size_t>(grid.nx) * grid.ny;
  for (auto* v : {&thickness_, &start_, &direction_x_, &direction_y_, &gradient_x_, &gradient_y_, &stress_xx_, &stress_xy_,
                  &stress_yy_})
    v->assign(cells, 0.0);
  force_x_.assign(static_cast<std::size_t>(grid.nx + 1) * grid.ny, 0.0);
  force_y_.assign(static_cast<std::size_t>(grid.nx) * (grid.ny + 1), 0.0);
}

std::size_t SurfaceRoller::memory_bytes() const {
  std::size_t bytes = 0;
  for (const auto* v : {&thickness_, &start_, &direction_x_, &direction_y_, &gradient_x_, &gradient_y_, &stress_xx_,
                        &stress_xy_, &stress_yy_, &force_x_, &force_y_})
    bytes += v->capacity() * sizeof(double);
  return bytes;
}

// tan(phi(t)): phi = phi_0 + (phi_B - phi_0) exp(-ln 2 t / t_1/2)   Madsen et al. (1997) eq. (8)
double SurfaceRoller::slope_of(double age_s) const {
  const double angle = k_.final_angle_rad + (k_.onset_angle_rad - k_.final_angle_rad) * std::exp2(-std::max(age_s, 0.0) / k_.half_time_s);
  return std::tan(angle);
}

// Walks a line of cells in the direction of travel's opposite, from the trough ahead of a front up
// to its crest: the toe is the first face where the surface falls towards the direction of travel
// more steeply than tan(phi) (projected on the line); from the toe a line rises backwards at that
// slope, and the water above it is the roller, until the surface drops below the line again (near
// the crest). A roller rides on a crest that moves its way: it is kept only when the water at its
// crest end flows in its direction of travel (the rear face of a crest is no front, however steep).
// Cells: first + i * step, i = 0..count-1; `direction` = +1: travel towards increasing i, -1 the
// other way.
void SurfaceRoller::scan_line(double now_s, const double* eta, const double* eta_previous, const double* flux_along, const double* start_time_s,
                              std::size_t first, std::ptrdiff_t step, int count, double spacing_m, bool along_x, int direction,
                              std::vector<std::pair<std::size_t, double>>& cells) {
  const float* depth = grid_.depth_m;
  auto cell = [&](int i) { return static_cast<std::size_t>(static_cast<std::ptrdiff_t>(first) + i * step); };
  auto wet = [&](std::size_t c) {
    return depth[c] > 0.0f && grid_.porosity[c] >= 1.0f && depth[c] + eta[c] > k_.dry_depth_m;
  };
  bool in_roller = false, front_rising = false;
  double line_level = 0.0, line_slope = 0.0, roller_start = 0.0, roller_nx = 0.0, roller_ny = 0.0;
  cells.clear();
  // The roller found so far is kept when the flux along the line at its last cell (the crest end)
  // runs in its direction of travel.
  auto close = [&]() {
    if (!cells.empty() && flux_along[cells.back().first] * direction > 0.0 && front_rising)
      for (const auto& [index, delta] : cells)
        if (delta > thickness_[index]) {
          thickness_[index] = delta;
          start_[index] = roller_start;
          direction_x_[index] = roller_nx;
          direction_y_[index] = roller_ny;
        }
    cells.clear();
    in_roller = false;
  };
  // i runs against the direction of travel: from the front (ahead) back to the crest.
  const int begin = direction > 0 ? count - 2 : 1, end = direction > 0 ? -1 : count, next = direction > 0 ? -1 : 1;
  for (int i = begin; i != end; i += next) {
    const std::size_t here = cell(i), ahead = cell(i - next);
    if (!wet(here)) {
      close();
      continue;
    }
    if (in_roller) {
      line_level += line_slope * spacing_m;
      const double delta = eta[here] - line_level;
      if (delta > kMinimumThickness_m) {
        cells.emplace_back(here, delta);
        continue;
      }
      close();
    }
    if (!wet(ahead)) continue;
    // The direction of travel of this front: down the surface gradient at the toe. The line's
    // slope along this grid line is tan(phi) times the share of the gradient along it, so an
    // oblique front gives the same thickness as a scan along its normal.
    const double gx = gradient_x_[ahead], gy = gradient_y_[ahead], magnitude = std::hypot(gx, gy);
    if (magnitude == 0.0) continue;
    const double along = (along_x ? -gx : -gy) / magnitude * direction;  // > 0: the front faces this way
    // Fronts more than 60 degrees off this grid line are the other scan's (its share is above
    // cos 30 deg there); this keeps a line from reading round-off across a long crest as a front.
    if (along < 0.5) continue;
    const double front_slope = (eta[here] - eta[ahead]) / spacing_m;  // rise from the toe backwards
    // The roller's age: a front whose toe region held a roller last step continues it (the oldest
    // start time there), so phi decays over the roller's life, not over its passage past a cell.
    double start = now_s;
    for (int j = i - 2 * next; j != i + 3 * next; j += next) {
      if (j < 0 || j >= count) continue;
      const double s = start_time_s[cell(j)];
      if (s >= 0.0) start = std::min(start, s);
    }
    const double threshold = slope_of(now_s - start) * along;
    if (front_slope <= threshold) continue;
    in_roller = true;
    // A front advances into the water ahead of it: the surface on it rises (eta_t > 0). The rear
    // faces of ripples riding behind a bore are steep too, but fall as the pattern passes.
    front_rising = eta[here] > eta_previous[here];
    line_slope = threshold;
    line_level = eta[ahead] + line_slope * spacing_m;
    roller_start = start;
    roller_nx = -gx / magnitude;
    roller_ny = -gy / magnitude;
    cells.emplace_back(here, eta[here] - line_level);
  }
  close();
}

void SurfaceRoller::smooth_stresses(const double* eta) {
  const int nx = grid_.nx, ny = grid_.ny;
  const float* depth = grid_.depth_m;
  auto at = [nx](int c, int r) { return static_cast<std::size_t>(r) * nx + c; };
  auto open = [&](std::size_t i) { return depth[i] > 0.0f && grid_.porosity[i] >= 1.0f && depth[i] + eta[i] > k_.dry_depth_m; };
  // One pass along x (rows) into `out`, or along y (columns) back; gradient_x_ serves as scratch.
  for (auto* stress : {&stress_xx_, &stress_xy_, &stress_yy_}) {
    double* values = stress->data();
    double* scratch = gradient_x_.data();
    for (int axis = 0; axis < (ny > 1 ? 2 : 1); ++axis) {
      const bool along_x = axis == 0;
      tbb::parallel_for(0, ny, [&](int r) {
        for (int c = 0; c < nx; ++c) {
          const std::size_t i = at(c, r);
          const int c_lo = along_x ? c - 1 : c, c_hi = along_x ? c + 1 : c, r_lo = along_x ? r : r - 1, r_hi = along_x ? r : r + 1;
          const bool lo_ok = c_lo >= 0 && r_lo >= 0 && open(at(c_lo, r_lo));
          const bool hi_ok = c_hi < nx && r_hi < ny && open(at(c_hi, r_hi));
          const double here = values[i];
          // What a cell gives its neighbours it takes from itself: (1/4) each side it can give to.
          double result = here * (0.5 + (lo_ok ? 0.0 : 0.25) + (hi_ok ? 0.0 : 0.25));
          if (lo_ok) result += 0.25 * values[at(c_lo, r_lo)] * (open(i) ? 1.0 : 0.0);
          if (hi_ok) result += 0.25 * values[at(c_hi, r_hi)] * (open(i) ? 1.0 : 0.0);
          scratch[i] = result;
        }
      });
      std::copy(scratch, scratch + thickness_.size(), values);
    }
  }
}

bool SurfaceRoller::update(double now_s, const double* eta, const double* eta_previous, const double* flux_x, const double* flux_y,
                           double* start_time_s, float* breaking_indicator) {
  const int nx = grid_.nx, ny = grid_.ny;
  const double dx = grid_.dx, dy = grid_.dy, g = ocean::kGravity_m_s2;
  const float* depth = grid_.depth_m;
  auto at = [nx](int c, int r) { return static_cast<std::size_t>(r) * nx + c; };
  auto wet = [&](std::size_t i) { return depth[i] > 0.0f && depth[i] + eta[i] > k_.dry_depth_m; };
  // 1. The surface gradient per cell: central differences, one-sided next to a dry cell or an edge.
  tbb::parallel_for(0, ny, [&](int r) {
    for (int c = 0; c < nx; ++c) {
      const std::size_t i = at(c, r);
      thickness_[i] = 0.0;
      start_[i] = -1.0;
      auto difference = [&](std::size_t lo, std::size_t hi, bool lo_ok, bool hi_ok, double spacing) {
        lo_ok = lo_ok && wet(lo);
        hi_ok = hi_ok && wet(hi);
        if (lo_ok && hi_ok) return (eta[hi] - eta[lo]) / (2.0 * spacing);
        if (hi_ok) return (eta[hi] - eta[i]) / spacing;
        if (lo_ok) return (eta[i] - eta[lo]) / spacing;
        return 0.0;
      };
      gradient_x_[i] = difference(c > 0 ? at(c - 1, r) : i, c + 1 < nx ? at(c + 1, r) : i, c > 0, c + 1 < nx, dx);
      gradient_y_[i] = difference(r > 0 ? at(c, r - 1) : i, r + 1 < ny ? at(c, r + 1) : i, r > 0, r + 1 < ny, dy);
    }
  });
  // 2. The rollers: scans along the rows (fronts travelling east and west), then along the
  // columns (north and south); a cell keeps the thickest roller found.
  // The flux along each scan at the cell centres (P for the rows, Q for the columns): stress_xx_
  // and stress_yy_ serve as scratch until step 3 writes them.
  double* flux_x_cell = stress_xx_.data();
  double* flux_y_cell = stress_yy_.data();
  tbb::parallel_for(0, ny, [&](int r) {
    for (int c = 0; c < nx; ++c) {
      flux_x_cell[at(c, r)] = 0.5 * (flux_x[static_cast<std::size_t>(c) * ny + r] + flux_x[static_cast<std::size_t>(c + 1) * ny + r]);
      flux_y_cell[at(c, r)] = 0.5 * (flux_y[at(c, r)] + flux_y[static_cast<std::size_t>(r + 1) * nx + c]);
    }
  });
  tbb::enumerable_thread_specific<std::vector<std::pair<std::size_t, double>>> roller_cells;
  tbb::parallel_for(0, ny, [&](int r) {
    for (int direction : {+1, -1})
      scan_line(now_s, eta, eta_previous, flux_x_cell, start_time_s, at(0, r), 1, nx, dx, true, direction, roller_cells.local());
  });
  if (ny > 1)
    tbb::parallel_for(0, nx, [&](int c) {
      for (int direction : {+1, -1})
        scan_line(now_s, eta, eta_previous, flux_y_cell, start_time_s, at(c, 0), nx, ny, dy, false, direction, roller_cells.local());
    });
  // 3. Thickness delta = f_delta times the height above the line, its momentum flux
  // R_ij = delta (c_i - u_i)(c_j - u_j) / (1 - delta/h) with c = celerity_factor sqrt(g h) along
  // the direction of travel and u = (P, Q)/h at the cell centre (Madsen et al. 1997 eq. 5-7).
  bool any = false;
  for (std::size_t i = 0, cells = thickness_.size(); i < cells; ++i) {
    const int c = static_cast<int>(i % nx), r = static_cast<int>(i / nx);
    start_time_s[i] = start_[i];
    double rxx = 0.0, rxy = 0.0, ryy = 0.0;
    if (thickness_[i] > 0.0) {
      any = true;
      const double h = depth[i] + eta[i];
      const double delta = std::min(k_.shape_factor * thickness_[i], kMaximumDepthShare * h);
      const double u = 0.5 * (flux_x[static_cast<std::size_t>(c) * ny + r] + flux_x[static_cast<std::size_t>(c + 1) * ny + r]) / h;
      const double v = 0.5 * (flux_y[at(c, r)] + flux_y[static_cast<std::size_t>(r + 1) * nx + c]) / h;
      const double celerity = k_.celerity_factor * std::sqrt(g * h);
      const double relative_u = celerity * direction_x_[i] - u, relative_v = celerity * direction_y_[i] - v;
      // Where the water under the front runs faster than the roller (c - u.n <= 0: swash tongues,
      // backwash) the roller picture, a surface layer carried by the wave over slower water,
      // does not hold: no roller.
      const double factor = relative_u * direction_x_[i] + relative_v * direction_y_[i] > 0.0 ? delta / (1.0 - delta / h) : 0.0;
      rxx = factor * relative_u * relative_u;
      rxy = factor * relative_u * relative_v;
      ryy = factor * relative_v * relative_v;
    }
    stress_xx_[i] = rxx;
    stress_xy_[i] = rxy;
    stress_yy_[i] = ryy;
    breaking_indicator[i] = thickness_[i] > 0.0 ? 1.0f : 0.0f;
  }
  if (!any) {
    std::fill(force_x_.begin(), force_x_.end(), 0.0);
    std::fill(force_y_.begin(), force_y_.end(), 0.0);
    return false;
  }
  // The roller is a few cells long: its edges (toe, crest end) fall on whole cells and jump by a
  // cell from one step to the next, a forcing at the grid scale that the scheme has no
  // dissipation for. A 1-2-1 filter of R along each axis (weights 1/4, 1/2, 1/4; wet open cells
  // only, the weight of a dry or edge neighbour kept by the cell itself) removes the 2 dx mode and
  // keeps the sum of R, so the total force of a roller is unchanged.
  smooth_stresses(eta);
  // 4. The force on the faces: -dR_xx/dx - dR_xy/dy on the x faces, -dR_xy/dx - dR_yy/dy on the y
  // faces; the cross derivative from the mean of the face's two cells one line either side (the
  // grid edge mirrored). Only between two wet open cells; walls and the grid edges carry none.
  auto open_wet = [&](std::size_t i) { return wet(i) && grid_.porosity[i] >= 1.0f; };
  tbb::parallel_for(0, ny, [&](int r) {
    const int rn = std::min(r + 1, ny - 1), rs = std::max(r - 1, 0);
    for (int f = 0; f <= nx; ++f) {
      double force = 0.0;
      if (f > 0 && f < nx && open_wet(at(f - 1, r)) && open_wet(at(f, r))) {
        const double across = rn == rs ? 0.0
                                       : (stress_xy_[at(f - 1, rn)] + stress_xy_[at(f, rn)] - stress_xy_[at(f - 1, rs)] -
                                          stress_xy_[at(f, rs)]) / (2.0 * (rn - rs) * dy);
        force = -(stress_xx_[at(f, r)] - stress_xx_[at(f - 1, r)]) / dx - across;
      }
      force_x_[static_cast<std::size_t>(f) * ny + r] = force;
    }
  });
  tbb::parallel_for(0, ny + 1, [&](int k) {
    for (int c = 0; c < nx; ++c) {
      double force = 0.0;
      if (k > 0 && k < ny && open_wet(at(c, k - 1)) && open_wet(at(c, k))) {
        const int ce = std::min(c + 1, nx - 1), cw = std::max(c - 1, 0);
        const double across = (stress_xy_[at(ce, k - 1)] + stress_xy_[at(ce, k)] - stress_xy_[at(cw, k - 1)] -
                               stress_xy_[at(cw, k)]) / (2.0 * (ce - cw) * dx);
        force = -(stress_yy_[at(c, k)] - stress_yy_[at(c, k - 1)]) / dy - across;
      }
      force_y_[static_cast<std::size_t>(k) * nx + c] = force;
    }
  });
  return true;
}

}  // namespace nearshore::boussinesq::detail
