#include "nearshore/ships/shallow_water.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>
#if defined(__SSE2__)
#include <xmmintrin.h>
#endif

#include "nearshore/core/error.hpp"

// The hot loops are built three times, for AVX-512 (x86-64-v4: 16 floats or 8 doubles per
// instruction), for AVX2 + FMA (x86-64-v3) and for the baseline, and the loader picks one (GCC
// function multiversioning): the library stays portable. The AVX-512 clone takes 12-18 % off the
// median step on this machine's Xeon, measured step by step against the AVX2 build in one process
// so that both see the same load (docs/ships.md, "Measured"). Not under the sanitizers (their
// runtime starts after the resolvers run).
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && !defined(__SANITIZE_ADDRESS__)
#define NEARSHORE_VECTOR_CLONES __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define NEARSHORE_VECTOR_CLONES
#endif

namespace nearshore::ships {
namespace {

// Subnormal numbers flushed to zero while a step runs (MXCSR FTZ and DAZ), the caller's mode put
// back after it. A wave's far field decays to values below the smallest normal float (1.2e-38;
// squares of small velocities get there first), and every x86 operation with a subnormal operand
// or result takes a microcode assist of about a hundred cycles: the bench's 256 x 256 step,
// a Gaussian hump on 10 m of water, took 2.2 times as long with them (docs/ships.md, "Measured").
// Flushing changes only values below 1.2e-38 (float) or 2.2e-308 (double), far below every
// tolerance of the scheme; exact zeros (a lake at rest, dry cells) stay exactly zero, and a depth
// flushed to 0 is still >= 0.
class SubnormalsFlushedToZero {
 public:
#if defined(__SSE2__)
  SubnormalsFlushedToZero() : saved_(_mm_getcsr()) { _mm_setcsr(saved_ | kFlushToZero | kDenormalsAreZero); }
  ~SubnormalsFlushedToZero() { _mm_setcsr(saved_); }
  SubnormalsFlushedToZero(const SubnormalsFlushedToZero&) = delete;
  SubnormalsFlushedToZero& operator=(const SubnormalsFlushedToZero&) = delete;

 private:
  static constexpr unsigned kFlushToZero = 0x8000, kDenormalsAreZero = 0x0040;  // MXCSR bits 15 and 6
  unsigned saved_;
#endif
};

// Larger and smaller of two values as selects (std::max returns a reference, which GCC does not
// if-convert inside a loop, so the loop would not vectorise).
template <class Real>
inline Real larger(Real a, Real b) {
  return a < b ? b : a;
}
template <class Real>
inline Real smaller(Real a, Real b) {
  return b < a ? b : a;
}

// Generalised minmod of three slopes, branch-free: the smallest when all are positive, the largest
// when all are negative, else 0 (max(low, 0) + min(high, 0) is exactly that).
template <class Real>
inline Real minmod3(Real a, Real b, Real c) {
  const Real low = smaller(a, smaller(b, c)), high = larger(a, larger(b, c));
  return larger(low, Real(0)) + smaller(high, Real(0));
}

// The desingularised 1/h of step 3 (KP eq. 2.17; seed 000 eq. 4.14-4.15):
// u = sqrt(2) h (hu) / sqrt(h^4 + max(h^4, eps)); exactly 1/h where h^4 >= eps, finite (0) at h = 0.
template <class Real>
inline Real desingularised_inverse_depth(Real h, Real epsilon) {
  const Real h4 = h * h * h * h;
  return Real(std::numbers::sqrt2) * h / std::sqrt(h4 + larger(h4, epsilon));
}

// Step 2 along one direction for n cells of a row: the state at the cells (w, normal, tangential)
// and at their neighbours behind and ahead (`*_behind_cell`, `*_ahead_cell`: the next cells in x,
// or the rows below and above in y, which may sit in a row buffer rather than in the grid), the
// bottom B' at the face ahead (b_ahead) and behind (b_behind). Writes the face values ahead and
// behind, and the well-balanced source of the normal momentum, -g hbar (B'_ahead - B'_behind) / dx,
// hbar the mean of the two face depths (KP eq. 3.11).
template <class Real>
NEARSHORE_VECTOR_CLONES void reconstruct_row(int n, Real theta, Real g_over_dx, const Real* __restrict w_behind_cell,
                                             const Real* __restrict w, const Real* __restrict w_ahead_cell,
                                             const Real* __restrict normal_behind_cell, const Real* __restrict normal,
                                             const Real* __restrict normal_ahead_cell,
                                             const Real* __restrict tangential_behind_cell,
                                             const Real* __restrict tangential,
                                             const Real* __restrict tangential_ahead_cell,
                                             const Real* __restrict b_ahead, const Real* __restrict b_behind,
                                             Real* __restrict w_ahead, Real* __restrict w_behind,
                                             Real* __restrict normal_ahead, Real* __restrict normal_behind,
                                             Real* __restrict tangential_ahead, Real* __restrict tangential_behind,
                                             Real* __restrict source) {
  const Real half(0.5);
  for (int i = 0; i < n; ++i) {
    // Half the limited slope times dx: the change from the centre to a face.
    const Real w_back = w[i] - w_behind_cell[i], w_next = w_ahead_cell[i] - w[i];
    const Real dw = half * minmod3(theta * w_back, half * (w_back + w_next), theta * w_next);
    const Real n_back = normal[i] - normal_behind_cell[i], n_next = normal_ahead_cell[i] - normal[i];
    const Real dn = half * minmod3(theta * n_back, half * (n_back + n_next), theta * n_next);
    const Real t_back = tangential[i] - tangential_behind_cell[i], t_next = tangential_ahead_cell[i] - tangential[i];
    const Real dt = half * minmod3(theta * t_back, half * (t_back + t_next), theta * t_next);
    // KP section 3.1: where a face value falls below the bottom there, the slope is changed so
    // that the depth there is 0 (the cell mean, and so its mass, is kept).
    const Real bh = b_ahead[i], bb = b_behind[i], centre = w[i];
    const Real ahead = centre + dw, behind = centre - dw;
    const bool dry_ahead = ahead < bh;
    const bool dry_behind = !dry_ahead & (behind < bb);
    const Real wa = dry_ahead ? bh : (dry_behind ? Real(2) * centre - bb : ahead);
    const Real wb = dry_ahead ? Real(2) * centre - bh : (dry_behind ? bb : behind);
    w_ahead[i] = wa;
    w_behind[i] = wb;
    normal_ahead[i] = normal[i] + dn;
    normal_behind[i] = normal[i] - dn;
    tangential_ahead[i] = tangential[i] + dt;
    tangential_behind[i] = tangential[i] - dt;
    source[i] = -g_over_dx * half * ((wa - bh) + (wb - bb)) * (bh - bb);
  }
}

// Steps 3-4 for n faces: the face values on the low side (l) and the high side (r) of each face,
// its bottom b. Writes the central-upwind flux (seed 000 eq. 4.11-4.13) of mass, normal and
// tangential momentum, and the face's largest |a|.
template <class Real>
NEARSHORE_VECTOR_CLONES void face_fluxes(int n, Real g, Real epsilon, const Real* __restrict w_l,
                                         const Real* __restrict normal_l, const Real* __restrict tangential_l,
                                         const Real* __restrict w_r, const Real* __restrict normal_r,
                                         const Real* __restrict tangential_r, const Real* __restrict b,
                                         Real* __restrict flux_mass, Real* __restrict flux_normal,
                                         Real* __restrict flux_tangential, Real* __restrict speed) {
  const Real zero(0), half(0.5);
  for (int i = 0; i < n; ++i) {
    const Real hl = larger(w_l[i] - b[i], zero), hr = larger(w_r[i] - b[i], zero);
    const Real inverse_l = desingularised_inverse_depth(hl, epsilon), inverse_r = desingularised_inverse_depth(hr, epsilon);
    const Real ul = inverse_l * normal_l[i], vl = inverse_l * tangential_l[i];
    const Real ur = inverse_r * normal_r[i], vr = inverse_r * tangential_r[i];
    const Real ql = hl * ul, qr = hr * ur;  // discharges recomputed from the velocities
    const Real cl = std::sqrt(g * hl), cr = std::sqrt(g * hr);
    const Real a_plus = larger(larger(ul + cl, ur + cr), zero);
    const Real a_minus = smaller(smaller(ul - cl, ur - cr), zero);
    const Real spread = a_plus - a_minus;
    const bool still = spread < Real(1e-14);  // both sides dry: no flux
    const Real inverse = still ? zero : Real(1) / (still ? Real(1) : spread);
    const Real product = a_plus * a_minus * inverse;
    const Real fl_normal = ql * ul + half * g * hl * hl, fr_normal = qr * ur + half * g * hr * hr;
    flux_mass[i] = (a_plus * ql - a_minus * qr) * inverse + product * (w_r[i] - w_l[i]);
    flux_normal[i] = (a_plus * fl_normal - a_minus * fr_normal) * inverse + product * (qr - ql);
    flux_tangential[i] = (a_plus * ql * vl - a_minus * qr * vr) * inverse + product * (hr * vr - hl * vl);
    speed[i] = larger(a_plus, -a_minus);
  }
}

// to = a + b for n values (w' = w + zeta of a row).
template <class Real>
NEARSHORE_VECTOR_CLONES void sum_row(int n, const Real* __restrict a, const Real* __restrict b, Real* __restrict to) {
  for (int i = 0; i < n; ++i) to[i] = a[i] + b[i];
}

// The rates of n cells of a row from its x fluxes (faces 0..n) and its two sources.
template <class Real>
NEARSHORE_VECTOR_CLONES void rates_from_x_fluxes(int n, Real inverse_dx, const Real* __restrict flux_mass,
                                                 const Real* __restrict flux_normal,
                                                 const Real* __restrict flux_tangential,
                                                 const Real* __restrict source_x, const Real* __restrict source_y,
                                                 Real* __restrict rate_w, Real* __restrict rate_hu,
                                                 Real* __restrict rate_hv) {
  for (int i = 0; i < n; ++i) {
    rate_w[i] = -inverse_dx * (flux_mass[i + 1] - flux_mass[i]);
    rate_hu[i] = -inverse_dx * (flux_normal[i + 1] - flux_normal[i]) + source_x[i];
    rate_hv[i] = -inverse_dx * (flux_tangential[i + 1] - flux_tangential[i]) + source_y[i];
  }
}

// Adds `sign / dx` times the y fluxes of a row of faces to a row's rates (+ below the face,
// - above it). Across a y face the normal momentum is hv, the tangential hu.
template <class Real>
NEARSHORE_VECTOR_CLONES void add_y_fluxes(int n, Real factor, const Real* __restrict flux_mass,
                                          const Real* __restrict flux_normal, const Real* __restrict flux_tangential,
                                          Real* __restrict rate_w, Real* __restrict rate_hu, Real* __restrict rate_hv) {
  for (int i = 0; i < n; ++i) {
    rate_w[i] += factor * flux_mass[i];
    rate_hv[i] += factor * flux_normal[i];
    rate_hu[i] += factor * flux_tangential[i];
  }
}

// One forward-Euler stage of a row (average: Heun's second stage, the mean with the old state),
// then the round-off clamp: a negative depth becomes 0, a dry cell has no discharge. `depth`
// receives each cell's depth before the clamp.
template <class Real, bool kAverage>
NEARSHORE_VECTOR_CLONES void euler_stage_row(int n, Real dt, const Real* __restrict from_w,
                                             const Real* __restrict from_hu, const Real* __restrict from_hv,
                                             const Real* __restrict rate_w, const Real* __restrict rate_hu,
                                             const Real* __restrict rate_hv, const Real* __restrict b_cell,
                                             Real* __restrict w, Real* __restrict hu, Real* __restrict hv,
                                             Real* __restrict depth) {
  const Real half(0.5), zero(0);
  for (int i = 0; i < n; ++i) {
    Real nw = from_w[i] + dt * rate_w[i], nhu = from_hu[i] + dt * rate_hu[i], nhv = from_hv[i] + dt * rate_hv[i];
    if constexpr (kAverage) {
      nw = half * (w[i] + nw);
      nhu = half * (hu[i] + nhu);
      nhv = half * (hv[i] + nhv);
    }
    const Real bottom = b_cell[i], h = nw - bottom;
    depth[i] = h;
    w[i] = h < zero ? bottom : nw;
    hu[i] = h > zero ? nhu : zero;
    hv[i] = h > zero ? nhv : zero;
  }
}

// The largest (kLargest) or smallest of n values, in eight independent lanes so that the loop
// vectorises without reassociating a single running maximum (which GCC allows only under
// -ffinite-math-only).
template <class Real, bool kLargest>
NEARSHORE_VECTOR_CLONES Real extreme_of(int n, const Real* __restrict values, Real start) {
  constexpr int kLanes = 8;
  Real lanes[kLanes];
  for (int k = 0; k < kLanes; ++k) lanes[k] = start;
  int i = 0;
  for (; i + kLanes <= n; i += kLanes)
    for (int k = 0; k < kLanes; ++k)
      lanes[k] = kLargest ? larger(lanes[k], values[i + k]) : smaller(lanes[k], values[i + k]);
  for (; i < n; ++i) lanes[0] = kLargest ? larger(lanes[0], values[i]) : smaller(lanes[0], values[i]);
  Real result = start;
  for (int k = 0; k < kLanes; ++k) result = kLargest ? larger(result, lanes[k]) : smaller(result, lanes[k]);
  return result;
}

}  // namespace

template <class Real>
BasicShallowWaterGrid<Real>::BasicShallowWaterGrid(int columns, int rows, double spacing_m, EdgeKind edges,
                                                   ShallowWaterOptions options)
    : columns_(columns), rows_(rows), spacing_m_(spacing_m), edges_(edges), options_(options) {
  if (columns < 2 || rows < 2 || !(spacing_m > 0.0))
    throw Error("ShallowWaterGrid", fmt::format("{} x {} cells of {} m", columns, rows, spacing_m),
                "use at least 2 x 2 cells and a positive spacing");
  stride_ = static_cast<std::size_t>(columns + 2 * kGhost);
  const std::size_t cells = stride_ * static_cast<std::size_t>(rows + 2 * kGhost);
  const std::size_t corners = (stride_ + 1) * static_cast<std::size_t>(rows + 2 * kGhost + 1);
  for (auto* v : {&w_, &hu_, &hv_, &b_east_, &b_north_, &b_cell_, &w1_, &hu1_, &hv1_, &rate_[0], &rate_[1], &rate_[2],
                  &head_cell_})
    v->assign(cells, Real(0));
  wp_rows_.assign(kWpRows * stride_, Real(0));
  for (auto& v : rate_rows_) v.assign(2 * stride_, Real(0));
  entered_.assign(cells, 0);
  bottom_corner_.assign(corners, 0.0);
  head_corner_.assign(corners, 0.0);
  for (RowFaces* faces : {&x_faces_, &y_faces_[0], &y_faces_[1]})
    for (auto* v : {&faces->w_high, &faces->w_low, &faces->normal_high, &faces->normal_low, &faces->tangential_high,
                    &faces->tangential_low, &faces->source})
      v->assign(stride_, Real(0));
  for (auto* v : {&flux_mass_, &flux_normal_, &flux_tangential_, &speed_, &depth_}) v->assign(stride_, Real(0));
  update_bottom();
}

template <class Real>
void BasicShallowWaterGrid<Real>::set_bottom_corner(int i, int j, double elevation_m) {
  bottom_corner_[corner(i, j)] = elevation_m;
}
template <class Real>
double BasicShallowWaterGrid<Real>::bottom_corner(int i, int j) const {
  return bottom_corner_[corner(i, j)];
}
template <class Real>
void BasicShallowWaterGrid<Real>::set_pressure_head_corner(int i, int j, double head_m) {
  head_corner_[corner(i, j)] = head_m;
}
template <class Real>
double BasicShallowWaterGrid<Real>::pressure_head_corner(int i, int j) const {
  return head_corner_[corner(i, j)];
}
template <class Real>
double BasicShallowWaterGrid<Real>::bottom_cell(int i, int j) const {
  return b_cell_[padded(i, j)];
}
template <class Real>
double BasicShallowWaterGrid<Real>::pressure_head_cell(int i, int j) const {
  return head_cell_[padded(i, j)];
}

template <class Real>
void BasicShallowWaterGrid<Real>::update_bottom() {
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
      b_east_[p] = static_cast<Real>(0.5 * (bp(i + 1, j) + bp(i + 1, j + 1)));
      b_north_[p] = static_cast<Real>(0.5 * (bp(i, j + 1) + bp(i + 1, j + 1)));
      // Mean of the four interface values = mean of the four corners.
      b_cell_[p] = static_cast<Real>(0.25 * (b(i, j) + b(i + 1, j) + b(i, j + 1) + b(i + 1, j + 1)));
      head_cell_[p] = static_cast<Real>(0.25 * (z(i, j) + z(i + 1, j) + z(i, j + 1) + z(i + 1, j + 1)));
    }
}

template <class Real>
double BasicShallowWaterGrid<Real>::total_volume_m3() const {
  double volume = 0.0;
  for (int j = 0; j < rows_; ++j)
    for (int i = 0; i < columns_; ++i) volume += static_cast<double>(depth_m(i, j));
  return volume * spacing_m_ * spacing_m_;
}

template <class Real>
double BasicShallowWaterGrid<Real>::stable_time_step_s() const {
  double speed = 0.0;
  const double g = options_.gravity_m_s2, epsilon = std::pow(options_.desingularisation_depth_m, 4);
  for (int j = 0; j < rows_; ++j)
    for (int i = 0; i < columns_; ++i) {
      const std::size_t p = padded(i, j);
      const double h = static_cast<double>(w_[p]) - static_cast<double>(b_cell_[p]);
      if (h <= 0.0) continue;
      const double inverse = desingularised_inverse_depth(h, epsilon);
      speed = std::max(speed, std::hypot(inverse * hu_[p], inverse * hv_[p]) + std::sqrt(g * h));
    }
  return speed > 0.0 ? options_.cfl * spacing_m_ / speed : 1e300;
}

template <class Real>
void BasicShallowWaterGrid<Real>::fill_ghosts(std::vector<Real>& w, std::vector<Real>& hu, std::vector<Real>& hv) const {
  const Real sign = edges_ == EdgeKind::kWall ? Real(-1) : Real(1);
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

template <class Real>
double BasicShallowWaterGrid<Real>::sweep(const std::vector<Real>& w, const std::vector<Real>& hu,
                                          const std::vector<Real>& hv, const EulerStage* euler) {
  const Real g = static_cast<Real>(options_.gravity_m_s2), theta = static_cast<Real>(options_.limiter_theta);
  const Real inverse_dx = static_cast<Real>(1.0 / spacing_m_), g_over_dx = g * inverse_dx;
  const Real epsilon = static_cast<Real>(std::pow(options_.desingularisation_depth_m, 4));
  const std::ptrdiff_t row = static_cast<std::ptrdiff_t>(stride_);
  const int columns = columns_;
  // w' = w + zeta (the pressure head acts as a raised bottom) of padded row r, made one row ahead
  // of the sweep into a ring of kWpRows rows: the y reconstruction of row r reads rows r - 1 .. r + 1.
  auto wp_row = [&](int r) { return wp_rows_.data() + static_cast<std::size_t>((r + kGhost) % kWpRows) * stride_; };
  auto make_wp_row = [&](int r) {
    const std::size_t p = padded(-kGhost, r);
    sum_row<Real>(static_cast<int>(stride_), w.data() + p, head_cell_.data() + p, wp_row(r));
  };
  // The rates of row r: the grid's rate arrays (no Euler stage: advance() needs the stage's local
  // speeds before it picks the step), else a ring of two rows, used as soon as a row is complete.
  auto rate_row = [&](int r, int k) -> Real* {
    if (euler == nullptr) return rate_[k].data() + padded(0, r);
    return rate_rows_[k].data() + static_cast<std::size_t>(r & 1) * stride_;
  };
  double max_speed = 0.0;
  Real lowest_depth(0);
  auto fastest = [&](int n) {  // only advance()'s first stage picks its step from the speeds
    if (euler == nullptr)
      max_speed = std::max(max_speed, static_cast<double>(extreme_of<Real, true>(n, speed_.data(), Real(0))));
  };
  make_wp_row(-kGhost);
  make_wp_row(-1);
  // One sweep over the rows r = -1 .. R (the ghost rows give the edge faces): the y faces of row r,
  // then (inner rows) its x faces, fluxes and rates, then the fluxes across the faces between row
  // r - 1 and row r, which close the rates of row r - 1 and add to those of row r; row r - 1 then
  // takes its Euler stage while its data are still in cache.
  for (int r = -1; r <= rows_; ++r) {
    make_wp_row(r + 1);
    RowFaces& y = y_faces_[(r + 1) & 1];
    const RowFaces& y_below = y_faces_[r & 1];
    const std::size_t p0 = padded(0, r);
    const Real* wp = wp_row(r) + kGhost;  // cell 0 of row r
    const Real *wp_south = wp_row(r - 1) + kGhost, *wp_north = wp_row(r + 1) + kGhost;
    reconstruct_row<Real>(columns, theta, g_over_dx, wp_south, wp, wp_north, hv.data() + p0 - row, hv.data() + p0,
                          hv.data() + p0 + row, hu.data() + p0 - row, hu.data() + p0, hu.data() + p0 + row,
                          b_north_.data() + p0, b_north_.data() + p0 - row, y.w_high.data(), y.w_low.data(),
                          y.normal_high.data(), y.normal_low.data(), y.tangential_high.data(),
                          y.tangential_low.data(), y.source.data());
    if (r >= 0 && r < rows_) {
      // Cells -1 .. C of the row; face k (0 .. C) lies between cells k - 1 and k.
      const std::size_t q0 = p0 - 1;
      RowFaces& x = x_faces_;
      reconstruct_row<Real>(columns + 2, theta, g_over_dx, wp - 2, wp - 1, wp, hu.data() + q0 - 1, hu.data() + q0,
                            hu.data() + q0 + 1, hv.data() + q0 - 1, hv.data() + q0, hv.data() + q0 + 1,
                            b_east_.data() + q0, b_east_.data() + q0 - 1, x.w_high.data(), x.w_low.data(),
                            x.normal_high.data(), x.normal_low.data(), x.tangential_high.data(),
                            x.tangential_low.data(), x.source.data());
      face_fluxes<Real>(columns + 1, g, epsilon, x.w_high.data(), x.normal_high.data(), x.tangential_high.data(),
                        x.w_low.data() + 1, x.normal_low.data() + 1, x.tangential_low.data() + 1,
                        b_east_.data() + q0, flux_mass_.data(), flux_normal_.data(), flux_tangential_.data(),
                        speed_.data());
      fastest(columns + 1);
      rates_from_x_fluxes<Real>(columns, inverse_dx, flux_mass_.data(), flux_normal_.data(), flux_tangential_.data(),
                                x.source.data() + 1, y.source.data(), rate_row(r, 0), rate_row(r, 1), rate_row(r, 2));
    }
    if (r >= 0) {
      face_fluxes<Real>(columns, g, epsilon, y_below.w_high.data(), y_below.normal_high.data(),
                        y_below.tangential_high.data(), y.w_low.data(), y.normal_low.data(), y.tangential_low.data(),
                        b_north_.data() + p0 - row, flux_mass_.data(), flux_normal_.data(), flux_tangential_.data(),
                        speed_.data());
      fastest(columns);
      if (r >= 1)
        add_y_fluxes<Real>(columns, -inverse_dx, flux_mass_.data(), flux_normal_.data(), flux_tangential_.data(),
                           rate_row(r - 1, 0), rate_row(r - 1, 1), rate_row(r - 1, 2));
      if (r < rows_)
        add_y_fluxes<Real>(columns, inverse_dx, flux_mass_.data(), flux_normal_.data(), flux_tangential_.data(),
                           rate_row(r, 0), rate_row(r, 1), rate_row(r, 2));
    }
    if (euler != nullptr && r >= 1)
      lowest_depth = smaller(lowest_depth, euler_row(*euler, r - 1, w, hu, hv, rate_row(r - 1, 0), rate_row(r - 1, 1),
                                                    rate_row(r - 1, 2)));
  }
  most_negative_depth_m_ = std::min(most_negative_depth_m_, static_cast<double>(lowest_depth));
  return max_speed;
}

template <class Real>
Real BasicShallowWaterGrid<Real>::euler_row(const EulerStage& stage, int j, const std::vector<Real>& from_w,
                                            const std::vector<Real>& from_hu, const std::vector<Real>& from_hv,
                                            const Real* rate_w, const Real* rate_hu, const Real* rate_hv) {
  const std::size_t p = padded(0, j);
  const Real dt = static_cast<Real>(stage.dt_s);
  const auto update = stage.average ? &euler_stage_row<Real, true> : &euler_stage_row<Real, false>;
  update(columns_, dt, from_w.data() + p, from_hu.data() + p, from_hv.data() + p, rate_w, rate_hu, rate_hv,
         b_cell_.data() + p, stage.w->data() + p, stage.hu->data() + p, stage.hv->data() + p, depth_.data());
  return extreme_of<Real, false>(columns_, depth_.data(), Real(0));
}

template <class Real>
void BasicShallowWaterGrid<Real>::stage(std::vector<Real>& from_w, std::vector<Real>& from_hu,
                                        std::vector<Real>& from_hv, double dt_s, bool average, std::vector<Real>& w,
                                        std::vector<Real>& hu, std::vector<Real>& hv) {
  fill_ghosts(from_w, from_hu, from_hv);
  const EulerStage euler{dt_s, average, &w, &hu, &hv};
  sweep(from_w, from_hu, from_hv, &euler);
}

template <class Real>
int BasicShallowWaterGrid<Real>::advance(double dt_s) {
  [[maybe_unused]] const SubnormalsFlushedToZero flushed;
  int steps = 0;
  double remaining = dt_s;
  while (remaining > 1e-12 * dt_s) {
    // Stage 1: its local speeds give the step, so its rates go to the rate arrays first.
    fill_ghosts(w_, hu_, hv_);
    const double speed = sweep(w_, hu_, hv_, nullptr);
    const double limit = speed > 0.0 ? options_.cfl * spacing_m_ / speed : remaining;
    const double dt = std::min(remaining, limit);
    // A state whose waves outrun any ship or tide (a non-finite speed, or so many steps that the
    // caller's frame could never finish) stops here instead of hanging the caller.
    if (!(dt > 0.0) || !std::isfinite(speed) || steps >= kMaxStepsPerAdvance)
      throw Error("shallow-water grid",
                  fmt::format("internal error: advancing {:.3g} s needs more than {} steps (fastest wave {:.3g} m/s)",
                              dt_s, kMaxStepsPerAdvance, speed),
                  "please report this with the ship or the grid that made it");
    const EulerStage first{dt, false, &w1_, &hu1_, &hv1_};
    Real lowest_depth(0);
    for (int j = 0; j < rows_; ++j)
      lowest_depth = smaller(lowest_depth, euler_row(first, j, w_, hu_, hv_, rate_[0].data() + padded(0, j),
                                                    rate_[1].data() + padded(0, j), rate_[2].data() + padded(0, j)));
    most_negative_depth_m_ = std::min(most_negative_depth_m_, static_cast<double>(lowest_depth));
    // Stage 2: U = (U + U1 + dt L(U1)) / 2.
    stage(w1_, hu1_, hv1_, dt, true, w_, hu_, hv_);
    remaining -= dt;
    ++steps;
  }
  return steps;
}

template <class Real>
void BasicShallowWaterGrid<Real>::step(double dt_s) {
  [[maybe_unused]] const SubnormalsFlushedToZero flushed;
  stage(w_, hu_, hv_, dt_s, false, w1_, hu1_, hv1_);
  stage(w1_, hu1_, hv1_, dt_s, true, w_, hu_, hv_);
}

template <class Real>
void BasicShallowWaterGrid<Real>::shift_window(int di, int dj) {
  std::fill(entered_.begin(), entered_.end(), 0);
  if (di == 0 && dj == 0) return;
  const std::vector<Real> w = w_, hu = hu_, hv = hv_;
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
        w_[p] = Real(0);
        hu_[p] = hv_[p] = Real(0);
        entered_[p] = 1;
      }
    }
}

template <class Real>
void BasicShallowWaterGrid<Real>::rest_new_cells() {
  for (int j = 0; j < rows_; ++j)
    for (int i = 0; i < columns_; ++i) {
      const std::size_t p = padded(i, j);
      if (entered_[p]) w_[p] = std::max(-head_cell_[p], b_cell_[p]);  // w' = w + zeta = 0 where wet
      if (w_[p] < b_cell_[p]) {
        w_[p] = b_cell_[p];
        hu_[p] = hv_[p] = Real(0);
      }
    }
  std::fill(entered_.begin(), entered_.end(), 0);
}

template class BasicShallowWaterGrid<double>;
template class BasicShallowWaterGrid<float>;

}  // namespace nearshore::ships
