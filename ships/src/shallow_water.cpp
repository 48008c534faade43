#include "nearshore/ships/shallow_water.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "nearshore/core/error.hpp"

namespace nearshore::ships {
namespace {

inline double minmod3(double a, double b, double c) {
  if (a > 0.0 && b > 0.0 && c > 0.0) return std::min(a, std::min(b, c));
  if (a < 0.0 && b < 0.0 && c < 0.0) return std::max(a, std::max(b, c));
  return 0.0;
}

// One side of an interface: depth, desingularised normal and tangential velocities, recomputed
// discharges (KP eq. 2.17; seed 000 eq. 4.14-4.15).
struct InterfaceState {
  double w, h, un, ut, qn, qt;
};

inline InterfaceState interface_state(double w, double b, double qn, double qt, double epsilon, double h_epsilon) {
  InterfaceState s;
  s.w = w;
  s.h = std::max(w - b, 0.0);
  if (s.h >= h_epsilon) {  // h^4 >= eps: the formula is exactly q / h
    const double inverse = 1.0 / s.h;
    s.un = qn * inverse;
    s.ut = qt * inverse;
  } else if (s.h > 0.0) {
    const double h4 = s.h * s.h * s.h * s.h;
    const double scale = std::sqrt(2.0) * s.h / std::sqrt(h4 + std::max(h4, epsilon));
    s.un = scale * qn;
    s.ut = scale * qt;
  } else {
    s.un = s.ut = 0.0;
  }
  s.qn = s.h * s.un;
  s.qt = s.h * s.ut;
  return s;
}

// Central-upwind flux (seed 000 eq. 4.11-4.13) across an interface with normal n: returns the
// largest |a| and writes (mass, normal momentum, tangential momentum).
inline double central_upwind(const InterfaceState& l, const InterfaceState& r, double g, double& f0, double& fn,
                             double& ft) {
  const double cl = std::sqrt(g * l.h), cr = std::sqrt(g * r.h);
  const double a_plus = std::max({l.un + cl, r.un + cr, 0.0});
  const double a_minus = std::min({l.un - cl, r.un - cr, 0.0});
  const double spread = a_plus - a_minus;
  if (spread < 1e-14) {
    f0 = fn = ft = 0.0;
    return 0.0;
  }
  const double fl0 = l.qn, fln = l.qn * l.un + 0.5 * g * l.h * l.h, flt = l.qn * l.ut;
  const double fr0 = r.qn, frn = r.qn * r.un + 0.5 * g * r.h * r.h, frt = r.qn * r.ut;
  const double inv = 1.0 / spread, product = a_plus * a_minus * inv;
  f0 = (a_plus * fl0 - a_minus * fr0) * inv + product * (r.w - l.w);
  fn = (a_plus * fln - a_minus * frn) * inv + product * (r.qn - l.qn);
  ft = (a_plus * flt - a_minus * frt) * inv + product * (r.qt - l.qt);
  return std::max(a_plus, -a_minus);
}

}  // namespace

ShallowWaterGrid::ShallowWaterGrid(int columns, int rows, double spacing_m, EdgeKind edges, ShallowWaterOptions options)
    : columns_(columns), rows_(rows), spacing_m_(spacing_m), edges_(edges), options_(options) {
  if (columns < 2 || rows < 2 || !(spacing_m > 0.0))
    throw Error("ShallowWaterGrid", fmt::format("{} x {} cells of {} m", columns, rows, spacing_m),
                "use at least 2 x 2 cells and a positive spacing");
  stride_ = static_cast<std::size_t>(columns + 2 * kGhost);
  const std::size_t cells = stride_ * static_cast<std::size_t>(rows + 2 * kGhost);
  const std::size_t corners = (stride_ + 1) * static_cast<std::size_t>(rows + 2 * kGhost + 1);
  for (auto* v : {&w_, &hu_, &hv_, &b_east_, &b_north_, &b_cell_, &w1_, &hu1_, &hv1_, &rate_w_, &rate_hu_, &rate_hv_,
                  &w_e_, &w_w_, &w_n_, &w_s_, &hu_e_, &hu_w_, &hu_n_, &hu_s_, &hv_e_, &hv_w_, &hv_n_, &hv_s_,
                  &head_cell_, &wp_})
    v->assign(cells, 0.0);
  entered_.assign(cells, 0);
  bottom_corner_.assign(corners, 0.0);
  head_corner_.assign(corners, 0.0);
  for (auto& f : flux_x_) f.assign(static_cast<std::size_t>(columns + 1) * rows, 0.0);
  for (auto& f : flux_y_) f.assign(static_cast<std::size_t>(columns) * (rows + 1), 0.0);
  update_bottom();
}

void ShallowWaterGrid::set_bottom_corner(int i, int j, double elevation_m) { bottom_corner_[corner(i, j)] = elevation_m; }
double ShallowWaterGrid::bottom_corner(int i, int j) const { return bottom_corner_[corner(i, j)]; }
void ShallowWaterGrid::set_pressure_head_corner(int i, int j, double head_m) { head_corner_[corner(i, j)] = head_m; }
double ShallowWaterGrid::pressure_head_corner(int i, int j) const { return head_corner_[corner(i, j)]; }
double ShallowWaterGrid::bottom_cell(int i, int j) const { return b_cell_[padded(i, j)]; }
double ShallowWaterGrid::pressure_head_cell(int i, int j) const { return head_cell_[padded(i, j)]; }

void ShallowWaterGrid::update_bottom() {
  // Ghost corners mirror the real ones, so ghost cells are the mirror images of edge cells.
  auto mirror = [](int k, int n) { return k < 0 ? -k : (k > n ? 2 * n - k : k); };
  for (auto* field : {&bottom_corner_, &head_corner_})
    for (int j = -kGhost; j <= rows_ + kGhost; ++j)
      for (int i = -kGhost; i <= columns_ + kGhost; ++i)
        if (i < 0 || j < 0 || i > columns_ || j > rows_)
          (*field)[corner(i, j)] = (*field)[corner(mirror(i, columns_), mirror(j, rows_))];
  // B' = B + zeta at the interfaces (means of two corners) and the cell mean (KP eq. 3.2-3.4).
  for (int j = -kGhost; j < rows_ + kGhost; ++j)
    for (int i = -kGhost; i < columns_ + kGhost; ++i) {
      auto bp = [&](int ci, int cj) { return bottom_corner_[corner(ci, cj)] + head_corner_[corner(ci, cj)]; };
      auto b = [&](int ci, int cj) { return bottom_corner_[corner(ci, cj)]; };
      auto z = [&](int ci, int cj) { return head_corner_[corner(ci, cj)]; };
      const std::size_t p = padded(i, j);
      b_east_[p] = 0.5 * (bp(i + 1, j) + bp(i + 1, j + 1));
      b_north_[p] = 0.5 * (bp(i, j + 1) + bp(i + 1, j + 1));
      // Mean of the four interface values = mean of the four corners.
      b_cell_[p] = 0.25 * (b(i, j) + b(i + 1, j) + b(i, j + 1) + b(i + 1, j + 1));
      head_cell_[p] = 0.25 * (z(i, j) + z(i + 1, j) + z(i, j + 1) + z(i + 1, j + 1));
    }
}

double ShallowWaterGrid::total_volume_m3() const {
  double volume = 0.0;
  for (int j = 0; j < rows_; ++j)
    for (int i = 0; i < columns_; ++i) volume += depth_m(i, j);
  return volume * spacing_m_ * spacing_m_;
}

double ShallowWaterGrid::stable_time_step_s() const {
  double speed = 0.0;
  const double g = options_.gravity_m_s2;
  for (int j = 0; j < rows_; ++j)
    for (int i = 0; i < columns_; ++i) {
      const std::size_t p = padded(i, j);
      const double h = w_[p] - b_cell_[p];
      if (h <= 0.0) continue;
      const InterfaceState s = interface_state(w_[p] + head_cell_[p], b_cell_[p] + head_cell_[p], hu_[p], hv_[p],
                                               std::pow(options_.desingularisation_depth_m, 4),
                                               options_.desingularisation_depth_m);
      speed = std::max(speed, std::hypot(s.un, s.ut) + std::sqrt(g * h));
    }
  return speed > 0.0 ? options_.cfl * spacing_m_ / speed : 1e300;
}

void ShallowWaterGrid::fill_ghosts(std::vector<double>& w, std::vector<double>& hu, std::vector<double>& hv) const {
  const double sign = edges_ == EdgeKind::kWall ? -1.0 : 1.0;
  for (int j = 0; j < rows_; ++j)
    for (int k = 1; k <= kGhost; ++k) {
      const std::size_t west = padded(-k, j), west_src = padded(k - 1, j);
      const std::size_t east = padded(columns_ - 1 + k, j), east_src = padded(columns_ - k, j);
      w[west] = w[west_src];
      hu[west] = sign * hu[west_src];
      hv[west] = hv[west_src];
      w[east] = w[east_src];
      hu[east] = sign * hu[east_src];
      hv[east] = hv[east_src];
    }
  for (int k = 1; k <= kGhost; ++k)
    for (int i = -kGhost; i < columns_ + kGhost; ++i) {
      const std::size_t south = padded(i, -k), south_src = padded(i, k - 1);
      const std::size_t north = padded(i, rows_ - 1 + k), north_src = padded(i, rows_ - k);
      w[south] = w[south_src];
      hu[south] = hu[south_src];
      hv[south] = sign * hv[south_src];
      w[north] = w[north_src];
      hu[north] = hu[north_src];
      hv[north] = sign * hv[north_src];
    }
}

double ShallowWaterGrid::rates(std::vector<double>& w, std::vector<double>& hu, std::vector<double>& hv) {
  const double dx = spacing_m_, half = 0.5 * dx, g = options_.gravity_m_s2, theta = options_.limiter_theta;
  const double h_epsilon = options_.desingularisation_depth_m, epsilon = std::pow(h_epsilon, 4);
  // w' = w + zeta (the pressure head acts as a raised bottom).
  for (std::size_t p = 0; p < w.size(); ++p) wp_[p] = w[p] + head_cell_[p];
  fill_ghosts(wp_, hu, hv);
  const std::ptrdiff_t sx = 1, sy = static_cast<std::ptrdiff_t>(stride_);

  // 1. Reconstruction with the positivity correction, cells i in [-1, C], j in [-1, R].
  for (int j = -1; j <= rows_; ++j)
    for (int i = -1; i <= columns_; ++i) {
      const std::size_t p = padded(i, j);
      auto slope = [&](const std::vector<double>& f, std::ptrdiff_t s) {
        const double back = f[p] - f[p - s], ahead = f[p + s] - f[p];
        return minmod3(theta * back, 0.5 * (back + ahead), theta * ahead);  // times 1/dx, times dx/2 below
      };
      const double be = b_east_[p], bw = b_east_[p - sx], bn = b_north_[p], bs = b_north_[p - sy];
      double dwx = 0.5 * slope(wp_, sx), dwy = 0.5 * slope(wp_, sy);
      double we = wp_[p] + dwx, ww = wp_[p] - dwx, wn = wp_[p] + dwy, ws = wp_[p] - dwy;
      if (we < be) {
        we = be;
        ww = 2.0 * wp_[p] - be;
      } else if (ww < bw) {
        ww = bw;
        we = 2.0 * wp_[p] - bw;
      }
      if (wn < bn) {
        wn = bn;
        ws = 2.0 * wp_[p] - bn;
      } else if (ws < bs) {
        ws = bs;
        wn = 2.0 * wp_[p] - bs;
      }
      w_e_[p] = we;
      w_w_[p] = ww;
      w_n_[p] = wn;
      w_s_[p] = ws;
      const double dux = 0.5 * slope(hu, sx), duy = 0.5 * slope(hu, sy);
      const double dvx = 0.5 * slope(hv, sx), dvy = 0.5 * slope(hv, sy);
      hu_e_[p] = hu[p] + dux;
      hu_w_[p] = hu[p] - dux;
      hu_n_[p] = hu[p] + duy;
      hu_s_[p] = hu[p] - duy;
      hv_e_[p] = hv[p] + dvx;
      hv_w_[p] = hv[p] - dvx;
      hv_n_[p] = hv[p] + dvy;
      hv_s_[p] = hv[p] - dvy;
    }
  (void)half;

  // 2. Fluxes across x faces (i + 1/2, j), i in [-1, C - 1], and y faces (i, j + 1/2).
  double max_speed = 0.0;
  for (int j = 0; j < rows_; ++j)
    for (int i = -1; i < columns_; ++i) {
      const std::size_t l = padded(i, j), r = l + 1;
      const double b = b_east_[l];
      const InterfaceState left = interface_state(w_e_[l], b, hu_e_[l], hv_e_[l], epsilon, h_epsilon);
      const InterfaceState right = interface_state(w_w_[r], b, hu_w_[r], hv_w_[r], epsilon, h_epsilon);
      double f0, fn, ft;
      max_speed = std::max(max_speed, central_upwind(left, right, g, f0, fn, ft));
      const std::size_t f = static_cast<std::size_t>(j) * (columns_ + 1) + static_cast<std::size_t>(i + 1);
      flux_x_[0][f] = f0;
      flux_x_[1][f] = fn;
      flux_x_[2][f] = ft;
    }
  for (int j = -1; j < rows_; ++j)
    for (int i = 0; i < columns_; ++i) {
      const std::size_t l = padded(i, j), r = l + stride_;
      const double b = b_north_[l];
      const InterfaceState low = interface_state(w_n_[l], b, hv_n_[l], hu_n_[l], epsilon, h_epsilon);
      const InterfaceState high = interface_state(w_s_[r], b, hv_s_[r], hu_s_[r], epsilon, h_epsilon);
      double f0, fn, ft;
      max_speed = std::max(max_speed, central_upwind(low, high, g, f0, fn, ft));
      const std::size_t f = static_cast<std::size_t>(j + 1) * columns_ + static_cast<std::size_t>(i);
      flux_y_[0][f] = f0;
      flux_y_[1][f] = ft;  // x momentum is tangential across a y face
      flux_y_[2][f] = fn;
    }

  // 3. Rates with the well-balanced source (KP eq. 3.11).
  const double inv_dx = 1.0 / dx;
  for (int j = 0; j < rows_; ++j)
    for (int i = 0; i < columns_; ++i) {
      const std::size_t p = padded(i, j);
      const std::size_t fe = static_cast<std::size_t>(j) * (columns_ + 1) + static_cast<std::size_t>(i + 1), fw = fe - 1;
      const std::size_t fn = static_cast<std::size_t>(j + 1) * columns_ + static_cast<std::size_t>(i), fs = fn - columns_;
      const double be = b_east_[p], bw = b_east_[p - sx], bn = b_north_[p], bs = b_north_[p - sy];
      const double hbar_x = 0.5 * ((w_e_[p] - be) + (w_w_[p] - bw));
      const double hbar_y = 0.5 * ((w_n_[p] - bn) + (w_s_[p] - bs));
      rate_w_[p] = -inv_dx * (flux_x_[0][fe] - flux_x_[0][fw] + flux_y_[0][fn] - flux_y_[0][fs]);
      rate_hu_[p] = -inv_dx * (flux_x_[1][fe] - flux_x_[1][fw] + flux_y_[1][fn] - flux_y_[1][fs]) -
                    g * hbar_x * (be - bw) * inv_dx;
      rate_hv_[p] = -inv_dx * (flux_x_[2][fe] - flux_x_[2][fw] + flux_y_[2][fn] - flux_y_[2][fs]) -
                    g * hbar_y * (bn - bs) * inv_dx;
    }
  return max_speed;
}

void ShallowWaterGrid::clamp_depths(std::vector<double>& w, std::vector<double>& hu, std::vector<double>& hv) {
  for (int j = 0; j < rows_; ++j)
    for (int i = 0; i < columns_; ++i) {
      const std::size_t p = padded(i, j);
      const double h = w[p] - b_cell_[p];
      if (h < 0.0) {
        most_negative_depth_m_ = std::min(most_negative_depth_m_, h);
        w[p] = b_cell_[p];
        hu[p] = hv[p] = 0.0;
      } else if (h == 0.0) {
        hu[p] = hv[p] = 0.0;
      }
    }
}

int ShallowWaterGrid::advance(double dt_s) {
  int steps = 0;
  double remaining = dt_s;
  while (remaining > 1e-12 * dt_s) {
    // Stage 1 (its local speeds give the step).
    const double speed = rates(w_, hu_, hv_);
    const double limit = speed > 0.0 ? options_.cfl * spacing_m_ / speed : remaining;
    const double dt = std::min(remaining, limit);
    for (int j = 0; j < rows_; ++j)
      for (int i = 0; i < columns_; ++i) {
        const std::size_t p = padded(i, j);
        w1_[p] = w_[p] + dt * rate_w_[p];
        hu1_[p] = hu_[p] + dt * rate_hu_[p];
        hv1_[p] = hv_[p] + dt * rate_hv_[p];
      }
    clamp_depths(w1_, hu1_, hv1_);
    // Stage 2: U = (U + U1 + dt L(U1)) / 2.
    rates(w1_, hu1_, hv1_);
    for (int j = 0; j < rows_; ++j)
      for (int i = 0; i < columns_; ++i) {
        const std::size_t p = padded(i, j);
        w_[p] = 0.5 * (w_[p] + w1_[p] + dt * rate_w_[p]);
        hu_[p] = 0.5 * (hu_[p] + hu1_[p] + dt * rate_hu_[p]);
        hv_[p] = 0.5 * (hv_[p] + hv1_[p] + dt * rate_hv_[p]);
      }
    clamp_depths(w_, hu_, hv_);
    remaining -= dt;
    ++steps;
  }
  return steps;
}

void ShallowWaterGrid::step(double dt_s) {
  rates(w_, hu_, hv_);
  for (int j = 0; j < rows_; ++j)
    for (int i = 0; i < columns_; ++i) {
      const std::size_t p = padded(i, j);
      w1_[p] = w_[p] + dt_s * rate_w_[p];
      hu1_[p] = hu_[p] + dt_s * rate_hu_[p];
      hv1_[p] = hv_[p] + dt_s * rate_hv_[p];
    }
  clamp_depths(w1_, hu1_, hv1_);
  rates(w1_, hu1_, hv1_);
  for (int j = 0; j < rows_; ++j)
    for (int i = 0; i < columns_; ++i) {
      const std::size_t p = padded(i, j);
      w_[p] = 0.5 * (w_[p] + w1_[p] + dt_s * rate_w_[p]);
      hu_[p] = 0.5 * (hu_[p] + hu1_[p] + dt_s * rate_hu_[p]);
      hv_[p] = 0.5 * (hv_[p] + hv1_[p] + dt_s * rate_hv_[p]);
    }
  clamp_depths(w_, hu_, hv_);
}

void ShallowWaterGrid::shift_window(int di, int dj) {
  std::fill(entered_.begin(), entered_.end(), 0);
  if (di == 0 && dj == 0) return;
  const std::vector<double> w = w_, hu = hu_, hv = hv_;
  for (int j = 0; j < rows_; ++j)
    for (int i = 0; i < columns_; ++i) {
      const int si = i + di, sj = j + dj;
      const std::size_t p = padded(i, j);
      if (si >= 0 && si < columns_ && sj >= 0 && sj < rows_) {
        const std::size_t q = padded(si, sj);
        w_[p] = w[q];
        hu_[p] = hu[q];
        hv_[p] = hv[q];
      } else {
        w_[p] = 0.0;
        hu_[p] = hv_[p] = 0.0;
        entered_[p] = 1;
      }
    }
}

void ShallowWaterGrid::rest_new_cells() {
  for (int j = 0; j < rows_; ++j)
    for (int i = 0; i < columns_; ++i) {
      const std::size_t p = padded(i, j);
      if (entered_[p]) w_[p] = std::max(-head_cell_[p], b_cell_[p]);  // w' = w + zeta = 0 where wet
      if (w_[p] < b_cell_[p]) {
        w_[p] = b_cell_[p];
        hu_[p] = hv_[p] = 0.0;
      }
    }
  std::fill(entered_.begin(), entered_.end(), 0);
}

}  // namespace nearshore::ships
