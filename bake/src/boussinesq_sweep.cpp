// The line sweep of the ADI scheme: seed 003 eq. (1)-(7) on one line of the staggered grid,
// time-centred (Crank-Nicolson) and solved by the double sweep (Thomas algorithm).
// docs/solver.md derives every coefficient below; the comments name the term of the paper.
#include "boussinesq_sweep.hpp"

#include <algorithm>
#include <cmath>

#include "nearshore/bake/wave_component.hpp"

namespace nearshore::bake::detail {

void SweepScratch::resize(int faces) {
  for (auto* v : {&lower, &diagonal, &upper, &right, &increment, &eta_half, &flux_half, &cell_term, &fixed_term,
                  &tangential_squared, &active})
    v->assign(static_cast<std::size_t>(faces), 0.0);
}

namespace {

// Solves lower[i] x[i-1] + diagonal[i] x[i] + upper[i] x[i+1] = right[i], i = 0..n-1, by the
// double sweep (Thomas algorithm). The systems here are diagonally dominant (docs/solver.md), so
// no pivoting is needed. Overwrites upper and right; the solution is written to x.
void solve_tridiagonal(int n, const double* lower, const double* diagonal, double* upper, double* right, double* x) {
  upper[0] /= diagonal[0];
  right[0] /= diagonal[0];
  for (int i = 1; i < n; ++i) {
    const double inverse_pivot = 1.0 / (diagonal[i] - lower[i] * upper[i - 1]);
    upper[i] *= inverse_pivot;
    right[i] = (right[i] - lower[i] * right[i - 1]) * inverse_pivot;
  }
  x[n - 1] = right[n - 1];
  for (int i = n - 2; i >= 0; --i) x[i] = right[i] - upper[i] * x[i + 1];
}

}  // namespace

void sweep_line(const StaticFrame& frame, const SweepConstants& k, const SweepInput& in, const SweepOutput& out,
                int r, SweepScratch& s) {
  const int cols = frame.cols, rows = frame.rows, faces = cols + 1;
  const double dx = frame.spacing_m, inv_dx = 1.0 / dx, inv_dx2 = inv_dx * inv_dx, inv_dx3 = inv_dx2 * inv_dx;
  const double dt = k.time_step_s, g = kGravity_m_s2;
  const double B = k.dispersion_coefficient, B3 = B + 1.0 / 3.0;
  const double dry = k.dry_depth_m;
  const double inverse_chezy2 = k.chezy_coefficient > 0.0 ? 1.0 / (k.chezy_coefficient * k.chezy_coefficient) : 0.0;
  const int r_north = std::min(r + 1, rows - 1), r_south = std::max(r - 1, 0);
  const bool has_north = r + 1 < rows, has_south = r > 0;

  const std::size_t cell0 = static_cast<std::size_t>(r) * cols;
  const std::size_t face0 = static_cast<std::size_t>(r) * faces;
  const double* depth = frame.depth_m.data() + cell0;
  const double* inv_n = frame.inverse_porosity.data() + cell0;
  const double* eta_old = in.eta_old + cell0;
  const double* eta_base = in.eta_base + cell0;
  const double* normal_old = in.normal_old + face0;
  const double* nu = in.eddy_viscosity + cell0;
  double* eta_new = out.eta_new + cell0;

  auto cell = [cols](int c, int row) { return static_cast<std::size_t>(row) * cols + c; };
  auto across_eta = [&](int c, int row) { return in.eta_across[cell(c, row)]; };
  auto across_depth = [&](int c, int row) {
    return std::max(frame.depth_m[cell(c, row)] + in.eta_across[cell(c, row)], dry);
  };
  auto across_normal = [&](int f, int row) { return in.normal_across[static_cast<std::size_t>(row) * faces + f]; };
  auto tangential = [&](int c, int face_row) { return in.tangential_half[static_cast<std::size_t>(face_row) * cols + c]; };
  auto tangential_rate = [&](int c, int face_row) { return in.tangential_rate[static_cast<std::size_t>(face_row) * cols + c]; };

  // 1. Which faces carry flux this step (moving shoreline, docs/solver.md "Wet and dry"): a face
  // is active when it is open and the water above the higher of its two beds is deeper than
  // dry_depth_m (so water can run up onto a dry cell, and a lake at rest stays at rest).
  std::vector<double>& increment = s.increment;
  for (int f = 0; f < faces; ++f) {
    const std::size_t face = face0 + f;
    bool active = frame.face_open[face] != 0;
    if (active) {
      const int left = f - 1, right = f;
      const double surface = std::max(eta_old[left], eta_old[right]);
      const double bed = std::min(depth[left], depth[right]);
      active = surface + bed > dry;
    }
    // diagonal < 0 marks an inactive face for the assembly below; its flux goes to 0.
    s.diagonal[f] = active ? 1.0 : -1.0;
    increment[f] = active ? in.normal_guess[face0 + f] : -normal_old[f];
  }

  // 2. The explicit terms built only from values ACROSS the lines (they do not change during the
  // iteration): cross convection (PQ/h)_y, the cross-derivative dispersive terms of Psi (eq. 4),
  // and the cross part of the eddy-viscosity stress (eq. 6).
  for (int f = 1; f < cols; ++f) {
    s.fixed_term[f] = 0.0;
    s.tangential_squared[f] = 0.0;
    if (s.diagonal[f] < 0.0) continue;
    const std::size_t face = face0 + f;
    const int L = f - 1, R = f;
    const double n_f = frame.face_porosity[face], inv_n_f = 1.0 / n_f;
    const double d = frame.face_depth_m[face];
    // (PQ/h)_y at the face from the two corners north and south of it.
    double corner_north = 0.0, corner_south = 0.0;
    if (has_north) {
      const double flux_t = 0.5 * (tangential(L, r + 1) + tangential(R, r + 1));
      const double flux_n = 0.5 * (across_normal(f, r) + across_normal(f, r + 1));
      const double h = 0.25 * (across_depth(L, r) + across_depth(R, r) + across_depth(L, r + 1) + across_depth(R, r + 1));
      corner_north = flux_n * flux_t / h;
    }
    if (has_south) {
      const double flux_t = 0.5 * (tangential(L, r) + tangential(R, r));
      const double flux_n = 0.5 * (across_normal(f, r) + across_normal(f, r - 1));
      const double h = 0.25 * (across_depth(L, r) + across_depth(R, r) + across_depth(L, r - 1) + across_depth(R, r - 1));
      corner_south = flux_n * flux_t / h;
    }
    double term = -inv_n_f * (corner_north - corner_south) * inv_dx;

    // Psi_x of seed 003 eq. (4) (Madsen & Sorensen 1992 eq. 12), the cross-derivative parts:
    //   -(B+1/3) d^2 Q_xyt - n B g d^3 eta_xyy - d d_x (Q_yt/6 + n B g d eta_yy) - d d_y (Q_xt/6 + n B g d eta_xy)
    const double w = frame.face_dispersion_weight[face] * (in.dispersive[cell0 + L] & in.dispersive[cell0 + R]);
    if (w > 0.0) {
      auto eta_yy = [&](int c) { return (across_eta(c, r_north) - 2.0 * across_eta(c, r) + across_eta(c, r_south)) * inv_dx2; };
      auto eta_y = [&](int c) { return (across_eta(c, r_north) - across_eta(c, r_south)) * 0.5 * inv_dx; };
      auto flux_yt = [&](int c) { return (tangential_rate(c, r + 1) - tangential_rate(c, r)) * inv_dx; };
      const double eta_yy_L = eta_yy(L), eta_yy_R = eta_yy(R);
      const double eta_xyy = (eta_yy_R - eta_yy_L) * inv_dx;
      const double eta_yy_face = 0.5 * (eta_yy_L + eta_yy_R);
      const double eta_xy = (eta_y(R) - eta_y(L)) * inv_dx;
      const double flux_yt_L = flux_yt(L), flux_yt_R = flux_yt(R);
      const double flux_xyt = (flux_yt_R - flux_yt_L) * inv_dx;
      const double flux_yt_face = 0.5 * (flux_yt_L + flux_yt_R);
      const double flux_xt = 0.5 * ((tangential_rate(R, r) - tangential_rate(L, r)) +
                                    (tangential_rate(R, r + 1) - tangential_rate(L, r + 1))) * inv_dx;
      const double slope_along = frame.face_slope_along[face], slope_across = frame.face_slope_across[face];
      const double nBgd = n_f * B * g * d;
      const double psi = -B3 * d * d * flux_xyt - nBgd * d * d * eta_xyy -
                         d * slope_along * (flux_yt_face / 6.0 + nBgd * eta_yy_face) -
                         d * slope_across * (flux_xt / 6.0 + nBgd * eta_xy);
      term -= w * psi;
    }

    // F_x of seed 003 eq. (6), cross part: -(d/dy) nu (P_y + Q_x), divided by n.
    const double nu_north = has_north ? 0.25 * (nu[L] + nu[R] + in.eddy_viscosity[cell(L, r + 1)] + in.eddy_viscosity[cell(R, r + 1)]) : 0.0;
    const double nu_south = has_south ? 0.25 * (nu[L] + nu[R] + in.eddy_viscosity[cell(L, r - 1)] + in.eddy_viscosity[cell(R, r - 1)]) : 0.0;
    if (nu_north > 0.0 || nu_south > 0.0) {
      const double stress_north = has_north ? nu_north * ((across_normal(f, r + 1) - across_normal(f, r)) +
                                                          (tangential(R, r + 1) - tangential(L, r + 1))) * inv_dx : 0.0;
      const double stress_south = has_south ? nu_south * ((across_normal(f, r) - across_normal(f, r - 1)) +
                                                          (tangential(R, r) - tangential(L, r))) * inv_dx : 0.0;
      term += inv_n_f * (stress_north - stress_south) * inv_dx;
    }
    s.fixed_term[f] = term;
    const double flux_t = 0.25 * (tangential(L, r) + tangential(R, r) + tangential(L, r + 1) + tangential(R, r + 1));
    s.tangential_squared[f] = flux_t * flux_t;
  }

  // 3. Iterate the time-centred terms that depend on this line's own unknowns.
  auto update_eta = [&]() {
    // seed 003 eq. (1): n (eta - E)/dt = -(1/2) d(increment)/dx  (the Crank-Nicolson half of the new flux)
    for (int c = 0; c < cols; ++c)
      eta_new[c] = eta_base[c] - 0.5 * dt * inv_dx * inv_n[c] * (increment[c + 1] - increment[c]);
  };
  double* saved_active = s.active.data();
  for (int f = 0; f < faces; ++f) saved_active[f] = s.diagonal[f];

  const int iterations = std::max(1, k.iterations);
  for (int iteration = 0; iteration < iterations; ++iteration) {
    update_eta();
    for (int c = 0; c < cols; ++c) s.eta_half[c] = 0.5 * (eta_old[c] + eta_new[c]);
    for (int f = 0; f < faces; ++f) s.flux_half[f] = normal_old[f] + 0.5 * increment[f];
    for (int c = 0; c < cols; ++c) {
      const double flux_c = 0.5 * (s.flux_half[c] + s.flux_half[c + 1]);
      const double h_c = std::max(depth[c] + s.eta_half[c], dry);
      s.cell_term[c] = flux_c * flux_c / h_c;  // P^2/h at the cell centre
    }
    // Beyond the ends of the line the grid edge is a wall: mirror ghost cells (-1 -> 0, -2 -> 1).
    auto eta_half_at = [&](int c) {
      if (c < 0) c = std::min(-1 - c, cols - 1);
      if (c >= cols) c = std::max(2 * cols - 1 - c, 0);
      return s.eta_half[c];
    };

    s.lower[0] = 0.0; s.upper[0] = 0.0; s.right[0] = -normal_old[0];
    s.lower[faces - 1] = 0.0; s.upper[faces - 1] = 0.0; s.right[faces - 1] = -normal_old[faces - 1];
    double* diagonal = s.diagonal.data();
    diagonal[0] = 1.0; diagonal[faces - 1] = 1.0;
    for (int f = 1; f < cols; ++f) {
      if (saved_active[f] < 0.0) {
        s.lower[f] = 0.0; s.upper[f] = 0.0; diagonal[f] = 1.0; s.right[f] = -normal_old[f];
        continue;
      }
      const std::size_t face = face0 + f;
      const int L = f - 1, R = f;
      const double n_f = frame.face_porosity[face], inv_n_f = 1.0 / n_f;
      const double d = frame.face_depth_m[face];
      const double h_L = depth[L] + s.eta_half[L], h_R = depth[R] + s.eta_half[R];
      double h_f = (h_L > dry && h_R > dry) ? d + 0.5 * (s.eta_half[L] + s.eta_half[R])
                                             : std::max(s.eta_half[L], s.eta_half[R]) + std::min(depth[L], depth[R]);
      h_f = std::max(h_f, dry);

      // Along-line explicit terms: convection (P^2/h)_x / n and the along parts of Psi_x:
      //   -n B g d^3 eta_xxx - d d_x n B g d 2 eta_xx   (time-centred, iterated)
      double along = -inv_n_f * (s.cell_term[R] - s.cell_term[L]) * inv_dx;
      const double w = frame.face_dispersion_weight[face] * (in.dispersive[cell0 + L] & in.dispersive[cell0 + R]);
      double D2 = 0.0, S1 = 0.0;
      if (w > 0.0) {
        const double e_m2 = eta_half_at(f - 2), e_m1 = s.eta_half[L], e_0 = s.eta_half[R], e_p1 = eta_half_at(f + 1);
        const double eta_xxx = (e_p1 - 3.0 * e_0 + 3.0 * e_m1 - e_m2) * inv_dx3;
        const double eta_xx = 0.5 * (e_p1 - e_0 - e_m1 + e_m2) * inv_dx2;
        const double slope_along = frame.face_slope_along[face];
        along += w * n_f * B * g * d * d * (d * eta_xxx + 2.0 * slope_along * eta_xx);
        // Implicit parts of Psi_x: -(B+1/3) d^2 P_xxt - (1/3) d d_x P_xt
        D2 = w * B3 * d * d * inv_dx2;
        S1 = w * d * slope_along * inv_dx / 6.0;
      }

      // Chezy friction g P |(P,Q)| / (h^2 C^2) and porous resistance n P (alpha + beta |(P,Q)|/h)
      // of eq. (2), divided by n, implicit (backward Euler) so any resistance stays stable.
      const double flux_magnitude = std::sqrt(s.flux_half[f] * s.flux_half[f] + s.tangential_squared[f]);
      const double resistance = g * flux_magnitude * inverse_chezy2 * inv_n_f / (h_f * h_f) +
                                n_f * (frame.face_porous_laminar_s[face] + frame.face_porous_turbulent_m[face] * flux_magnitude / h_f);

      // Gravity n g h eta_x at t^{n+1/2} with eta* = E - dt/(2 n dx) d(increment): couples three faces.
      const double G = n_f * g * h_f * dt * dt * inv_dx2 * 0.25;
      // Eddy viscosity along the line, (1/n) d/dx (nu dP/dx), Crank-Nicolson.
      const double V_L = 0.5 * dt * nu[L] * inv_n_f * inv_dx2, V_R = 0.5 * dt * nu[R] * inv_n_f * inv_dx2;

      s.lower[f] = -D2 + S1 - G * inv_n[L] - V_L;
      s.upper[f] = -D2 - S1 - G * inv_n[R] - V_R;
      diagonal[f] = 1.0 + 2.0 * D2 + G * (inv_n[L] + inv_n[R]) + V_L + V_R + resistance * dt;
      const double gravity = -dt * n_f * g * h_f * 0.5 * inv_dx * (eta_base[R] - eta_base[L] + eta_old[R] - eta_old[L]);
      const double eddy_old = 2.0 * (V_R * (normal_old[f + 1] - normal_old[f]) - V_L * (normal_old[f] - normal_old[f - 1]));
      s.right[f] = gravity + dt * (s.fixed_term[f] + along) - resistance * dt * normal_old[f] + eddy_old;
    }
    solve_tridiagonal(faces, s.lower.data(), diagonal, s.upper.data(), s.right.data(), increment.data());
  }
  update_eta();
  double* normal_new = out.normal_new + face0;
  for (int f = 0; f < faces; ++f) normal_new[f] = normal_old[f] + increment[f];
}

namespace {
template <class T>
void transpose_blocked(const T* in, T* out, int cols, int rows) {
  constexpr int kBlock = 32;
  for (int r0 = 0; r0 < rows; r0 += kBlock)
    for (int c0 = 0; c0 < cols; c0 += kBlock) {
      const int r1 = std::min(rows, r0 + kBlock), c1 = std::min(cols, c0 + kBlock);
      for (int r = r0; r < r1; ++r)
        for (int c = c0; c < c1; ++c)
          out[static_cast<std::size_t>(c) * rows + r] = in[static_cast<std::size_t>(r) * cols + c];
    }
}
}  // namespace

void transpose(const double* in, double* out, int cols, int rows) { transpose_blocked(in, out, cols, rows); }
void transpose(const std::uint8_t* in, std::uint8_t* out, int cols, int rows) { transpose_blocked(in, out, cols, rows); }

}  // namespace nearshore::bake::detail
