// The explicit remainder of the fully nonlinear dispersive terms (nonlinear_dispersion.hpp; docs/solver.md
// "Fully nonlinear dispersion"). Five passes over the grid, each element-wise (the result does not
// depend on the thread count): eta and h at t^{n+1/2} per cell, kinematics per cell, Gamma per cell,
// the shallow-water residual's divergence per cell, the remainder on the x and y faces together
// (one pass over the rows) with its extrapolation to the next step. A value two rows share (a y
// face's velocity, Q^2/h of a cell, PQ/h of a corner, a cell's stencil mask) is computed once per
// chunk of rows and handed to the next row, by the same expression: the same bits as computing it
// for each row (issue 43: the remainder was 21 % of a default step).
//
// Each cell quantity comes twice: "for x" leaves out what the x sweep holds implicitly (the rate of
// the x-face fluxes P_t), "for y" what the y sweep holds (Q_t); the x faces take the first, the y
// faces the second.
#include "nonlinear_dispersion.hpp"

#include "boussinesq_sweep.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include <tbb/parallel_for.h>

#include "nearshore/ocean/wave_component.hpp"

namespace nearshore::boussinesq::detail {

NonlinearDispersion::NonlinearDispersion(const NonlinearDispersionGrid& grid) : grid_(grid) {
  const std::size_t faces_x = static_cast<std::size_t>(grid.nx + 1) * grid.ny;
  const std::size_t faces_y = static_cast<std::size_t>(grid.nx) * (grid.ny + 1);
  force_x_.assign(faces_x, 0.0f);
  last_x_.assign(faces_x, 0.0f);
  force_y_.assign(faces_y, 0.0f);
  last_y_.assign(faces_y, 0.0f);
  subcritical_x_.assign(faces_x, 0.0f);
  subcritical_y_.assign(faces_y, 0.0f);
}

void NonlinearDispersion::reset() {
  for (auto* v : {&force_x_, &force_y_, &last_x_, &last_y_}) std::fill(v->begin(), v->end(), 0.0f);
  evaluations_ = 0;
}

std::size_t NonlinearDispersion::memory_bytes() const {
  return (force_x_.capacity() + force_y_.capacity() + last_x_.capacity() + last_y_.capacity() + subcritical_x_.capacity() +
          subcritical_y_.capacity()) *
         sizeof(float);
}

namespace {

// The four neighbours of cell (c, r) the terms read, the cell itself beyond the grid's edges and
// where the neighbour is a wall (the solver's mask in the natural layout, the y sweep's frame:
// its lines are the columns, so kMirrorSouth / kMirrorNorth are the cells west / east of it and
// kMirrorBefore / kMirrorAfter the ones south / north; boussinesq_sweep.hpp).
struct Neighbours {
  int west, east, south, north;
};
// `mirror_walls` false (the default's mask has no wall bits): the mask is not read.
__attribute__((always_inline)) inline Neighbours neighbours(bool mirror_walls, const unsigned char* dispersive, int nx, int ny, int c,
                                                            int r) {
  Neighbours n{std::max(c - 1, 0), std::min(c + 1, nx - 1), std::max(r - 1, 0), std::min(r + 1, ny - 1)};
  if (!mirror_walls) return n;
  const unsigned flags = dispersive[static_cast<std::size_t>(r) * nx + c];
  if (flags & kMirrorSouth) n.west = c;
  if (flags & kMirrorNorth) n.east = c;
  if (flags & kMirrorBefore) n.south = r;
  if (flags & kMirrorAfter) n.north = r;
  return n;
}

}  // namespace

void NonlinearDispersion::update_subcritical(const double* eta, const double* flux_x, const double* flux_y,
                                             const unsigned char* dispersive, double* scratch, double* scratch_around) {
  const int nx = grid_.nx, ny = grid_.ny;
  const double dry = grid_.dry_depth_m;
  auto cell = [nx](int c, int r) { return static_cast<std::size_t>(r) * nx + c; };
  // Each cell's own factor, from its speed (the mean of its faces' velocities).
  tbb::parallel_for(0, ny, [&](int r) {
    for (int c = 0; c < nx; ++c) {
      const std::size_t i = cell(c, r);
      const double d = grid_.depth_m[i], h = d + eta[i];
      double weight = 0.0;
      if (grid_.porosity[i] == 1.0f && h > dry) {
        const double u = 0.5 * (flux_x[static_cast<std::size_t>(c) * ny + r] + flux_x[static_cast<std::size_t>(c + 1) * ny + r]) / h;
        const double v = 0.5 * (flux_y[cell(c, r)] + flux_y[cell(c, r + 1)]) / h;
        weight = subcritical_weight(std::sqrt(u * u + v * v), h, dry);
      }
      scratch[i] = weight;
    }
  });
  // The least over each cell and its neighbours (beyond the grid edge or a wall, the cell itself),
  // once per cell: each serves the four faces around the cell.
  tbb::parallel_for(0, ny, [&](int r) {
    for (int c = 0; c < nx; ++c) {
      const Neighbours n = neighbours(grid_.mirror_walls, dispersive, nx, ny, c, r);
      scratch_around[cell(c, r)] = std::min({scratch[cell(c, r)], scratch[cell(n.west, r)], scratch[cell(n.east, r)],
                                             scratch[cell(c, n.south)], scratch[cell(c, n.north)]});
    }
  });
  // A face: the least over its two cells' values.
  const double* around = scratch_around;
  tbb::parallel_for(0, ny, [&](int r) {
    for (int f = 0; f <= nx; ++f)
      subcritical_x_[static_cast<std::size_t>(f) * ny + r] =
          f == 0 || f == nx ? 0.0f : static_cast<float>(std::min(around[cell(f - 1, r)], around[cell(f, r)]));
  });
  tbb::parallel_for(0, ny + 1, [&](int k) {
    for (int c = 0; c < nx; ++c)
      subcritical_y_[cell(c, k)] = k == 0 || k == ny ? 0.0f : static_cast<float>(std::min(around[cell(c, k - 1)], around[cell(c, k)]));
  });
}

namespace {

// What the passes of NonlinearDispersion::update share: the step, the grid and the cell arrays at
// t^{n+1/2} (the caller's scratch), with the definitions every pass uses (the sweep's).
struct RemainderStep {
  const StepPair& s;
  const NonlinearDispersionGrid& grid;
  int nx, ny;
  double inv_dx, inv_dy, inv_dt, g, B, dry;
  const float* depth;
  // eta and h = d + eta (at least dry) at t^{n+1/2}, the cell velocities, div u, Gamma; then div S
  // and div S_linear reuse div u's and u's storage.
  double *divergence, *gamma, *eta, *h, *u_cell, *v_cell, *div_S, *div_S_linear;

  RemainderStep(const StepPair& pair, const NonlinearDispersionGrid& g_, double* const scratch[6])
      : s(pair), grid(g_), nx(g_.nx), ny(g_.ny), inv_dx(1.0 / g_.dx), inv_dy(1.0 / g_.dy), inv_dt(1.0 / pair.time_step_s),
        g(ocean::kGravity_m_s2), B(g_.dispersion_coefficient), dry(g_.dry_depth_m), depth(g_.depth_m), divergence(scratch[0]),
        gamma(scratch[1]), eta(scratch[2]), h(scratch[3]), u_cell(scratch[4]), v_cell(scratch[5]), div_S(scratch[0]),
        div_S_linear(scratch[4]) {}

  std::size_t cell(int c, int r) const { return static_cast<std::size_t>(r) * nx + c; }
  std::size_t face_x(int f, int r) const { return static_cast<std::size_t>(f) * ny + r; }
  std::size_t face_y(int c, int k) const { return static_cast<std::size_t>(k) * nx + c; }
  double flux_x(int f, int r) const { const std::size_t i = face_x(f, r); return s.flux_x_new[i] - 0.5 * s.flux_x_change[i]; }
  double flux_y(int c, int k) const { const std::size_t i = face_y(c, k); return s.flux_y_new[i] - 0.5 * s.flux_y_change[i]; }
  double eta_rate(std::size_t i) const { return (s.eta_new[i] - s.eta_old[i]) * inv_dt; }
  // The still-water and total depth of the face between cells a and b (the sweep's definitions).
  double face_still(std::size_t a, std::size_t b) const { return 0.5 * (static_cast<double>(depth[a]) + static_cast<double>(depth[b])); }
  double face_total(std::size_t a, std::size_t b) const { return std::max(face_still(a, b) + 0.5 * (eta[a] + eta[b]), dry); }
  // Rows go in chunks with their own row buffers (face values computed once per row). body(r, first,
  // buffers): `first` when r opens its chunk; a row after it finds in the buffers what the row before
  // left there (the values of the faces and cells the two rows share, computed once, by the same
  // expression as for the first row: the same bits).
  template <class Body>
  void for_rows(const Body& body) const {
    tbb::parallel_for(tbb::blocked_range<int>(0, ny, 8), [&](const tbb::blocked_range<int>& rows) {
      std::vector<double> buffers[8];
      for (auto& buffer : buffers) buffer.resize(nx + 1);
      for (int r = rows.begin(); r < rows.end(); ++r) body(r, r == rows.begin(), buffers);
    });
  }
};

// 0. Per cell: eta and the total depth at t^{n+1/2}.
void half_step_depths(const RemainderStep& t) {
  const StepPair& s = t.s;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, static_cast<std::size_t>(t.nx) * t.ny, 16384), [&](const tbb::blocked_range<std::size_t>& range) {
    for (std::size_t i = range.begin(); i < range.end(); ++i) {
      t.eta[i] = 0.5 * (s.eta_old[i] + s.eta_new[i]);
      t.h[i] = std::max(static_cast<double>(t.depth[i]) + t.eta[i], t.dry);
    }
  });
}

// 1. Per cell: div u, the cell velocities, and the part of div u_t - (div u)^2 without the flux
// rates (the sweeps hold those: along their lines implicitly, across them with the seed's across
// estimates): u_t = (P_t - u h_t)/h leaves -u h_t / h. Walls (the grid edges) carry nothing.
void cell_kinematics(const RemainderStep& t) {
  const int nx = t.nx, ny = t.ny;
  t.for_rows([&](int r, bool first_row, std::vector<double>* b) {
    std::vector<double>&u = b[0], &u_rate = b[1], &v_south = b[2], &v_rate_south = b[3], &v_north = b[4], &v_rate_north = b[5];
    auto face = [&](std::size_t a, std::size_t c, double flux, double& velocity, double& rate) {
      const double inv_h = 1.0 / t.face_total(a, c);
      velocity = flux * inv_h;
      rate = -velocity * 0.5 * (t.eta_rate(a) + t.eta_rate(c)) * inv_h;
    };
    u[0] = u_rate[0] = u[nx] = u_rate[nx] = 0.0;
    // Open edges (an imposed current, NonlinearDispersionGrid::open_edges): the edge face's flux over
    // its one cell's depth.
    const bool open = t.grid.open_edges;
    if (open) {
      face(t.cell(0, r), t.cell(0, r), t.flux_x(0, r), u[0], u_rate[0]);
      face(t.cell(nx - 1, r), t.cell(nx - 1, r), t.flux_x(nx, r), u[nx], u_rate[nx]);
    }
    for (int f = 1; f < nx; ++f) face(t.cell(f - 1, r), t.cell(f, r), t.flux_x(f, r), u[f], u_rate[f]);
    // The y faces south of the row are the ones north of the row before (its buffers, swapped in).
    if (first_row)
      for (int c = 0; c < nx; ++c) {
        v_south[c] = v_rate_south[c] = 0.0;
        if (r > 0) face(t.cell(c, r - 1), t.cell(c, r), t.flux_y(c, r), v_south[c], v_rate_south[c]);
        else if (open) face(t.cell(c, 0), t.cell(c, 0), t.flux_y(c, 0), v_south[c], v_rate_south[c]);
      }
    else {
      v_south.swap(v_north);
      v_rate_south.swap(v_rate_north);
    }
    for (int c = 0; c < nx; ++c) {
      v_north[c] = v_rate_north[c] = 0.0;
      if (r + 1 < ny) face(t.cell(c, r), t.cell(c, r + 1), t.flux_y(c, r + 1), v_north[c], v_rate_north[c]);
      else if (open) face(t.cell(c, r), t.cell(c, r), t.flux_y(c, ny), v_north[c], v_rate_north[c]);
    }
    for (int c = 0; c < nx; ++c) {
      const double div = (u[c + 1] - u[c]) * t.inv_dx + (v_north[c] - v_south[c]) * t.inv_dy;
      const std::size_t i = t.cell(c, r);
      t.divergence[i] = div;
      t.gamma[i] = (u_rate[c + 1] - u_rate[c]) * t.inv_dx + (v_rate_north[c] - v_rate_south[c]) * t.inv_dy - div * div;
      t.u_cell[i] = 0.5 * (u[c] + u[c + 1]);
      t.v_cell[i] = 0.5 * (v_south[c] + v_north[c]);
    }
  });
}

// 2. Per cell: h^3 Gamma, Gamma = (div u_t without the rates) + u . grad(div u) - (div u)^2 (the
// gradient central; beyond a grid edge, a wall, the cell mirrors itself). Linearised it is 0.
void cell_serre_term(const RemainderStep& t) {
  const int nx = t.nx, ny = t.ny;
  const StepPair& s = t.s;
  tbb::parallel_for(0, ny, [&](int r) {
    for (int c = 0; c < nx; ++c) {
      const auto [west, east, south, north] = neighbours(t.grid.mirror_walls, s.dispersive, nx, ny, c, r);
      const std::size_t i = t.cell(c, r);
      const double advection = t.u_cell[i] * (t.divergence[t.cell(east, r)] - t.divergence[t.cell(west, r)]) * (0.5 * t.inv_dx) +
                               t.v_cell[i] * (t.divergence[t.cell(c, north)] - t.divergence[t.cell(c, south)]) * (0.5 * t.inv_dy);
      // Where waves break the cell's share fades by 1 - B, inside the derivative of step 4
      // (conservation form: the fade adds no force of its own).
      const double keep = s.breaking_strength ? 1.0 - static_cast<double>(s.breaking_strength[i]) : 1.0;
      t.gamma[i] = keep * t.h[i] * t.h[i] * t.h[i] * (t.gamma[i] + advection);
    }
  });
}

// 3. Per cell: div S and its linearisation without the rates, S = div((P, Q)(P, Q)/h) + g h grad(eta)
// at the faces (S_linear = g d grad(eta)). The momentum fluxes as the sweep's central scheme
// builds them: P^2/h at the cell centres, PQ/h at the corners (zero on a wall).
void cell_residual_divergence(const RemainderStep& t) {
  const int nx = t.nx, ny = t.ny;
  const double inv_dx = t.inv_dx, inv_dy = t.inv_dy, g = t.g;
  const double* eta = t.eta;
  const double* h = t.h;
  auto along_x = [&](int c, int r) {  // P^2/h at cell (c, r)
    const double P = 0.5 * (t.flux_x(c, r) + t.flux_x(c + 1, r));
    return P * P / h[t.cell(c, r)];
  };
  auto along_y = [&](int c, int r) {  // Q^2/h
    const double Q = 0.5 * (t.flux_y(c, r) + t.flux_y(c, r + 1));
    return Q * Q / h[t.cell(c, r)];
  };
  auto corner = [&](int f, int k) {  // PQ/h at the corner between cells (f-1..f, k-1..k), inside the grid
    const double P = 0.5 * (t.flux_x(f, k - 1) + t.flux_x(f, k)), Q = 0.5 * (t.flux_y(f - 1, k) + t.flux_y(f, k));
    return 4.0 * P * Q / (h[t.cell(f - 1, k - 1)] + h[t.cell(f, k - 1)] + h[t.cell(f - 1, k)] + h[t.cell(f, k)]);
  };
  t.for_rows([&](int r, bool first_row, std::vector<double>* b) {
    // Row buffers: P^2/h of this row's cells, Q^2/h of the rows below, here and above, the corners
    // south (k = r) and north (k = r + 1) of the row, S and S_linear on the row's x faces. After the
    // first row of a chunk, the row before's Q^2/h here and above and its north corners are this
    // row's below and here and its south corners (rotated, not recomputed).
    std::vector<double>&along = b[0], &along_south = b[1], &along_here = b[2], &along_north = b[3], &corner_south = b[4],
                        &corner_north = b[5], &residual = b[6], &residual_linear = b[7];
    for (int c = 0; c < nx; ++c) along[c] = along_x(c, r);
    if (first_row) {
      for (int c = 0; c < nx; ++c) {
        along_here[c] = along_y(c, r);
        along_south[c] = r > 0 ? along_y(c, r - 1) : 0.0;
      }
      for (int f = 0; f <= nx; ++f) corner_south[f] = 0.0;
      if (r > 0)
        for (int f = 1; f < nx; ++f) corner_south[f] = corner(f, r);
    } else {
      along_south.swap(along_here);  // along_south = the row before's here
      along_here.swap(along_north);  // along_here = the row before's north; along_north: free
      corner_south.swap(corner_north);
    }
    for (int c = 0; c < nx; ++c) along_north[c] = r + 1 < ny ? along_y(c, r + 1) : 0.0;
    for (int f = 0; f <= nx; ++f) corner_north[f] = 0.0;
    if (r + 1 < ny)
      for (int f = 1; f < nx; ++f) corner_north[f] = corner(f, r + 1);
    residual[0] = residual[nx] = residual_linear[0] = residual_linear[nx] = 0.0;  // the walls: nothing
    const unsigned char* mask = t.s.dispersive;
    const bool mirror_walls = t.grid.mirror_walls;
    for (int f = 1; f < nx; ++f) {
      const std::size_t L = t.cell(f - 1, r), R = t.cell(f, r);
      if (mirror_walls && ((mask[L] & kMirrorNorth) | (mask[R] & kMirrorSouth))) {  // a wall inside the grid: nothing either
        residual[f] = residual_linear[f] = 0.0;
        continue;
      }
      const double slope = (eta[R] - eta[L]) * inv_dx;
      residual[f] = (along[f] - along[f - 1]) * inv_dx + (corner_north[f] - corner_south[f]) * inv_dy + g * t.face_total(L, R) * slope;
      residual_linear[f] = g * t.face_still(L, R) * slope;
    }
    for (int c = 0; c < nx; ++c) {
      const std::size_t i = t.cell(c, r);
      // S on the y faces south (k = r) and north (k = r + 1) of the cell; a wall carries nothing.
      double south = 0.0, north = 0.0, south_linear = 0.0, north_linear = 0.0;
      if (r > 0 && !(mirror_walls && ((mask[i] & kMirrorBefore) | (mask[t.cell(c, r - 1)] & kMirrorAfter)))) {
        const std::size_t below = t.cell(c, r - 1);
        const double slope = (eta[i] - eta[below]) * inv_dy;
        south = (corner_south[c + 1] - corner_south[c]) * inv_dx + (along_here[c] - along_south[c]) * inv_dy + g * t.face_total(below, i) * slope;
        south_linear = g * t.face_still(below, i) * slope;
      }
      if (r + 1 < ny && !(mirror_walls && ((mask[i] & kMirrorAfter) | (mask[t.cell(c, r + 1)] & kMirrorBefore)))) {
        const std::size_t above = t.cell(c, r + 1);
        const double slope = (eta[above] - eta[i]) * inv_dy;
        north = (corner_north[c + 1] - corner_north[c]) * inv_dx + (along_north[c] - along_here[c]) * inv_dy + g * t.face_total(i, above) * slope;
        north_linear = g * t.face_still(i, above) * slope;
      }
      t.div_S[i] = (residual[c + 1] - residual[c]) * inv_dx + (north - south) * inv_dy;
      t.div_S_linear[i] = (residual_linear[c + 1] - residual_linear[c]) * inv_dx + (north_linear - south_linear) * inv_dy;
    }
  });
}

}  // namespace

void NonlinearDispersion::update(const StepPair& s, double* const scratch[6]) {
  const RemainderStep t(s, grid_, scratch);
  half_step_depths(t);
  cell_kinematics(t);
  cell_serre_term(t);
  cell_residual_divergence(t);
  const int nx = t.nx, ny = t.ny;
  const double inv_dx = t.inv_dx, inv_dy = t.inv_dy, B = t.B, dry = t.dry;
  const double *eta = t.eta, *gamma = t.gamma, *div_S = t.div_S, *div_S_linear = t.div_S_linear;
  auto cell = [&t](int c, int r) { return t.cell(c, r); };
  auto face_x = [&t](int f, int r) { return t.face_x(f, r); };
  auto face_y = [&t](int c, int k) { return t.face_y(c, k); };
  auto face_still = [&t](std::size_t a, std::size_t b) { return t.face_still(a, b); };
  // 4. Per face: R = w [-(1/3) d(k h^3 Gamma) - k_face B (h^2 d(div S) - d^2 d(div S_linear))], k = 1 minus
  // the cell's breaking strength (1 without the fade), k_face the mean of the face's two, w = the taper
  // times fully_nonlinear_weight times the face's subcritical factor of this step (update_subcritical)
  // where the whole stencil (two cells on each side) is wet (0 elsewhere; the subcritical factor is 0
  // next to porous cells); then the force of the next step, extrapolated to its t^{n+3/2}.
  // (A wall beside a cell is read as the cell itself, as the grid's edges are: neighbours().)
  auto wide_mask = [&](int c, int r) {
    const unsigned char* m = s.dispersive;
    const Neighbours n = neighbours(grid_.mirror_walls, m, nx, ny, c, r);
    return m[cell(c, r)] & m[cell(n.west, r)] & m[cell(n.east, r)] & m[cell(c, n.south)] & m[cell(c, n.north)] & kDispersive;
  };
  auto remainder = [&](std::size_t L, std::size_t R, double inv_spacing, double taper, bool whole_stencil, float subcritical) {
    if (!whole_stencil || taper == 0.0 || subcritical == 0.0f) return 0.0;
    const double d = face_still(L, R), elevation = 0.5 * (eta[L] + eta[R]), h_face = std::max(d + elevation, dry);
    const double weight = taper * fully_nonlinear_weight(elevation, d, dry) * subcritical;
    if (weight == 0.0) return 0.0;
    const double serre = -(gamma[R] - gamma[L]) * inv_spacing / 3.0;
    const double enhancement = -B * (h_face * h_face * (div_S[R] - div_S[L]) - d * d * (div_S_linear[R] - div_S_linear[L])) * inv_spacing;
    const double keep_face = s.breaking_strength ? 1.0 - 0.5 * (static_cast<double>(s.breaking_strength[L]) + s.breaking_strength[R]) : 1.0;
    return weight * (serre + keep_face * enhancement);
  };
  const bool first = evaluations_ == 0;
  auto advance = [&](std::size_t i, double now, std::vector<float>& force, std::vector<float>& last) {
    force[i] = static_cast<float>(first ? now : 2.0 * now - static_cast<double>(last[i]));
    last[i] = static_cast<float>(now);
  };
  // One pass over the rows for both kinds of face: row r's x faces and the y faces south of it
  // (k = r; the last chunk also takes k = ny), each cell's wide mask formed once per row (a chunk's
  // later rows find the row before's in the other buffer).
  tbb::parallel_for(tbb::blocked_range<int>(0, ny, 8), [&](const tbb::blocked_range<int>& rows) {
    std::vector<unsigned char> wide_here(nx), wide_before(nx);
    for (int r = rows.begin(); r < rows.end(); ++r) {
      if (r == rows.begin()) {
        if (r > 0)
          for (int c = 0; c < nx; ++c) wide_before[c] = static_cast<unsigned char>(wide_mask(c, r - 1));
      } else {
        wide_before.swap(wide_here);
      }
      for (int c = 0; c < nx; ++c) wide_here[c] = static_cast<unsigned char>(wide_mask(c, r));
      for (int f = 0; f <= nx; ++f) {
        double now = 0.0;
        if (f > 0 && f < nx)
          now = remainder(cell(f - 1, r), cell(f, r), inv_dx, grid_.face_weight_x[face_x(f, r)], wide_here[f - 1] & wide_here[f],
                          subcritical_x_[face_x(f, r)]);
        advance(face_x(f, r), now, force_x_, last_x_);
      }
      for (int c = 0; c < nx; ++c) {
        double now = 0.0;
        if (r > 0)
          now = remainder(cell(c, r - 1), cell(c, r), inv_dy, grid_.face_weight_y[face_y(c, r)], wide_before[c] & wide_here[c],
                          subcritical_y_[face_y(c, r)]);
        advance(face_y(c, r), now, force_y_, last_y_);
      }
      if (r + 1 == ny)
        for (int c = 0; c < nx; ++c) advance(face_y(c, ny), 0.0, force_y_, last_y_);
    }
  });
  evaluations_ = std::min(evaluations_ + 1, 2);
}

}  // namespace nearshore::boussinesq::detail
