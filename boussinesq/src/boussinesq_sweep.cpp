// The line sweep of the ADI scheme: seed 003 eq. (1)-(7) on one line of the staggered grid,
// time-centred (Crank-Nicolson) and solved by the double sweep (Thomas algorithm).
// docs/solver.md derives every coefficient below; the comments name the term of the paper.
#include "boussinesq_sweep.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <type_traits>

#include <tbb/parallel_for.h>

#include "nearshore/ocean/wave_component.hpp"
#include "nonlinear_dispersion.hpp"

namespace nearshore::boussinesq::detail {

using namespace nearshore::ocean;  // wave components, sea states, linear waves

namespace {

// Every array of a SweepScratch, one list for sizing and for counting them.
template <class Scratch, class Visit>
void for_each_array(Scratch& s, const Visit& visit) {
  for (auto* v : {&s.upper, &s.right, &s.increment, &s.eta_half, &s.flux_half, &s.cell_term, &s.fixed_term,
                  &s.tangential_squared, &s.active, &s.face_velocity, &s.h_pair_north, &s.h_pair_south, &s.cell_eta_yy,
                  &s.cell_eta_y, &s.cell_flux_yt, &s.cell_slope_across, &s.nu_pair_north, &s.nu_pair_south,
                  &s.dispersion_weight, &s.mirror_before, &s.mirror_after, &s.mirror_south, &s.mirror_north})
    visit(*v);
}

}  // namespace

void SweepScratch::resize(int cols) {
  const std::size_t size = static_cast<std::size_t>(cols + 5) * kBlockLines;
  for_each_array(*this, [size](std::vector<double>& v) { v.assign(size, 0.0); });
}

std::size_t SweepScratch::memory_bytes() const {
  std::size_t bytes = 0;
  for_each_array(*this, [&bytes](const std::vector<double>& v) { bytes += v.capacity() * sizeof(double); });
  return bytes;
}

namespace {

// body(std::true_type{}) or body(std::false_type{}): a run-time switch made a compile-time one
// for the loop inside `body`. GCC vectorises no select on a loop-invariant bool (the loop stays
// scalar), so the sweep's options are decided outside its loops over the lines.
template <class Body>
__attribute__((always_inline)) inline void with_constant(bool flag, const Body& body) {
  if (flag)
    body(std::true_type{});
  else
    body(std::false_type{});
}

// The body of sweep_lines. kFullBlock: the block holds exactly kBlockLines lines, so every
// lock-step loop over the lines has a trip count the compiler knows (whole vectors, no remainder).
// kOpenWater: no face of the block is porous and no cell breaks (n = 1, alpha = beta = nu = 0), so
// those arrays are not read; the arithmetic left is the same, so the results are the same bits.
// kMirrorWalls: SweepConstants::mirror_walls (walls read as mirrors); without it the default's
// stencils stay as they were, with no extra array streamed per face (a bake measured 5-8 % slower
// with the blends always on).
// Always inlined into sweep_lines, so each of its instruction-set clones gets its own copy.
// The velocity P/h of the grid's two edge faces of a block's lines when they hold an imposed current
// (SweepConstants::edges_hold_flux): h is the edge cell's total depth (the ghost beyond it mirrors
// its level). Out of line and never vectorised: inlined into the vectorised sweep, this loop's
// max() stopped GCC 12 with an internal error (gimple_expand_vec_cond_expr) in the wall-mirroring
// clone, and so did the call under a condition in the sweep: the condition is tested in here. It
// runs over two faces per line.
__attribute__((noinline, optimize("no-tree-vectorize"))) void edge_face_velocities(
    const float* depth, const double* eta_half, const double* flux_half, double* face_velocity, int cols, std::size_t stride,
    int lb, int n, double dry, bool held) {
  if (!held) return;
  constexpr int W = kBlockLines;
  for (int j = 0; j < n; ++j) {
    const double h_west = std::max(static_cast<double>(depth[lb + j]) + eta_half[j], dry);
    const double h_east = std::max(static_cast<double>(depth[(cols - 1) * stride + lb + j]) + eta_half[(cols - 1) * W + j], dry);
    face_velocity[j] = flux_half[j] / h_west;
    face_velocity[cols * W + j] = flux_half[cols * W + j] / h_east;
  }
}

template <bool kFullBlock, bool kOpenWater, bool kMirrorWalls>
__attribute__((always_inline)) inline void sweep_block(const StaticFrame& frame, const SweepConstants& k,
                                                       const SweepInput& in, const SweepOutput& out, const int lb,
                                                       const int le, SweepScratch& s) {
  constexpr int W = kBlockLines;
  const int cols = frame.cols, rows = frame.rows, faces = cols + 1, n = kFullBlock ? W : le - lb;
  const std::size_t stride = static_cast<std::size_t>(rows), tstride = static_cast<std::size_t>(rows) + 1;
  // dx: along the sweep (the line's own derivatives), dy: across it (between lines). With square
  // cells dy = dx and every expression below is the one of the square scheme, bit for bit (the
  // aspect ratio dx/dy is then exactly 1).
  const double dx = frame.spacing_along_m, inv_dx = 1.0 / dx, inv_dx2 = inv_dx * inv_dx, inv_dx3 = inv_dx2 * inv_dx;
  const double dy = frame.spacing_across_m, inv_dy = 1.0 / dy, inv_dy2 = inv_dy * inv_dy, aspect = dx / dy;
  const double dt = k.time_step_s, g = kGravity_m_s2;
  const double B = k.dispersion_coefficient, B3 = B + 1.0 / 3.0;
  const double dry = k.dry_depth_m;
  const bool total_depth_dispersion = k.dispersion_on_total_depth;
  const bool fully_nonlinear_along = k.fully_nonlinear;  // along-line and across rate terms (nonlinear_dispersion.hpp)
  // mean_face_depth_where_wet: a face takes the mean depth when both cells are deeper than this, i.e.
  // wet (dry_depth_m), or never (infinity). A threshold rather than a flag ANDed in the loop: GCC
  // cannot vectorise a select on a loop-invariant bool.
  const double mean_face_wet_depth = k.mean_face_depth_where_wet ? dry : std::numeric_limits<double>::infinity();
  // The explicit cross stress d/dy (nu P_y) is stable for nu dt / dy^2 <= 0.2 (docs/solver.md).
  const double nu_explicit_max = 0.2 * dy * dy / dt;
  const double inverse_chezy2 = k.chezy_coefficient > 0.0 ? 1.0 / (k.chezy_coefficient * k.chezy_coefficient) : 0.0;
  const double laminar_film_factor = 3.0 * k.kinematic_viscosity_m2_s;  // 3 nu of tau_b = 3 rho nu u / h

  const float* __restrict depth = frame.depth_m.data();
  const float* __restrict porosity = frame.porosity.data();
  const float* __restrict inv_n = frame.inverse_porosity.data();
  const double* __restrict eta_old = in.eta_old;
  const double* __restrict eta_base = in.eta_base;
  const double* __restrict eta_partner = in.eta_across_partner;
  const bool eta_extrapolates = in.eta_across_extrapolates;
  const double* __restrict normal_old = in.normal_old;
  const double* __restrict tangential = in.tangential_half;
  const double* __restrict tangential_rate = in.tangential_rate;
  const EddyViscosity* __restrict nu = in.eddy_viscosity;
  const unsigned char* __restrict dispersive = in.dispersive;
  const float* __restrict face_weight = frame.face_dispersion_weight.data();
  const double* __restrict normal_guess = in.normal_guess;
  // The fully nonlinear terms' subcritical factor per face of this step, 0 at porous faces (the
  // terms act in open water, n = 1; nonlinear_dispersion.hpp).
  const float* __restrict subcritical = in.fully_nonlinear_subcritical;
  // The breaking strength by which the fully nonlinear terms fade, per cell (zeros when they do not).
  const float* __restrict breaking = in.fully_nonlinear_breaking;
  // Porous resistance (Van Gent 1995) of a face from its porosity, as build_frame describes it.
  const double laminar_factor = frame.porous_laminar_factor, turbulent_factor = frame.porous_turbulent_factor;
  const double stone_diameter = frame.porous_stone_diameter_m;
  const StoneDiameterRatio stone_ratio = StoneDiameterRatio::of(frame);
  // The face values the frame does not store (boussinesq_sweep.hpp); faces 0 and cols are walls of
  // depth 0 (with an imposed current the edges' own depth is set apart below, edges_hold_flux).
  auto depth_at_face = [&](int f, std::size_t face) __attribute__((always_inline)) {
    return f == 0 || f == cols ? 0.0 : face_depth(depth, face - stride, face);
  };
  // With an imposed current the edge faces keep their flux (increment 0, not -P_old).
  const double edge_release_factor = k.edge_release_factor;
  // eta at t^{n+1/2} for the derivatives across the lines, and the normal flux likewise (SweepInput).
  // `extrapolates`: eta_extrapolates as std::true_type or std::false_type (with_constant).
  auto eta_across = [&](auto extrapolates, std::size_t i) __attribute__((always_inline)) {
    const double here = eta_old[i], partner = eta_partner[i];
    if constexpr (decltype(extrapolates)::value)
      return here + 0.5 * (here - partner);
    else
      return 0.5 * (here + partner);
  };
  auto normal_across = [&](std::size_t face) __attribute__((always_inline)) {
    return normal_old[face] + 0.5 * normal_guess[face];
  };
  double* __restrict eta_new = out.eta_new;
  double* __restrict normal_new = out.normal_new;
  double* __restrict increment = s.increment.data();
  double* __restrict active = s.active.data();
  double* __restrict fixed_term = s.fixed_term.data();
  double* __restrict tangential_squared = s.tangential_squared.data();
  double* __restrict face_velocity = s.face_velocity.data();
  double* __restrict eta_half = s.eta_half.data() + 2 * W;  // two ghost cells before and after the line
  double* __restrict flux_half = s.flux_half.data();
  double* __restrict cell_term = s.cell_term.data();
  double* __restrict upper = s.upper.data();
  double* __restrict right = s.right.data();
  double* __restrict dispersion_weight = s.dispersion_weight.data();

  // 1. Which faces carry flux this step (moving shoreline, docs/solver.md "Wet and dry"): a face
  // is active when it is open and the water above the higher of its two beds is deeper than
  // dry_depth_m (so water can run up onto a dry cell, and a lake at rest stays at rest).
  #pragma GCC ivdep
  for (int j = 0; j < n; ++j)
    for (int f : {0, cols}) {  // grid edges: walls, or holding the imposed current's flux
      active[f * W + j] = 0.0;
      increment[f * W + j] = -normal_old[f * stride + lb + j] * edge_release_factor;
    }
  for (int f = 1; f < cols; ++f)
    #pragma GCC ivdep
    for (int j = 0; j < n; ++j) {
      const std::size_t face = f * stride + lb + j, L = face - stride, R = face;
      const double eta_L = eta_old[L], eta_R = eta_old[R];
      const float depth_L = depth[L], depth_R = depth[R];
      const double wet = std::max(eta_L, eta_R) + std::min(depth_L, depth_R) > dry ? 1.0 : 0.0;
      const double on = face_open(inv_n, L, R) * wet;
      active[f * W + j] = on;
      const double guess = normal_guess[face], closed = -normal_old[face];
      increment[f * W + j] = on != 0.0 ? guess : closed;
    }
  // The weight of the dispersive terms at each face: the taper times the dispersion mask of both
  // cells. Formed once here, as double: a byte in the loops below would make GCC's vectorisation
  // factor 64 lanes, more than a block has, and leave them scalar.
  for (int f = 1; f < cols; ++f)
    #pragma GCC ivdep
    for (int j = 0; j < n; ++j) {
      const std::size_t face = f * stride + lb + j;
      dispersion_weight[f * W + j] = face_weight[face] * (static_cast<double>(dispersive[face - stride] & kDispersive) *
                                                          static_cast<double>(dispersive[face] & kDispersive));
    }
  // The walls the stencils reach, as 0 or 1 in double (mark_dispersive): along the line, the cell
  // before a face's west cell and after its east cell (eta_xxx, eta_xx); across it, the lines
  // south and north of each cell (the per-cell cross terms below).
  double* __restrict mirror_before = s.mirror_before.data();
  double* __restrict mirror_after = s.mirror_after.data();
  double* __restrict mirror_south = s.mirror_south.data();
  double* __restrict mirror_north = s.mirror_north.data();
  if constexpr (kMirrorWalls)
  for (int c = 0; c < cols; ++c)
    #pragma GCC ivdep
    for (int j = 0; j < n; ++j) {
      // Face c + 1 has this cell on its west side, face c on its east side. (Bits shifted, not
      // selected with ?:, on which GCC 12 stops with an internal error vectorising this loop.)
      const int flags = dispersive[c * stride + lb + j];
      mirror_before[(c + 1) * W + j] = static_cast<double>((flags / kMirrorBefore) & 1);
      mirror_after[c * W + j] = static_cast<double>((flags / kMirrorAfter) & 1);
      mirror_south[c * W + j] = static_cast<double>((flags / kMirrorSouth) & 1);
      mirror_north[c * W + j] = static_cast<double>((flags / kMirrorNorth) & 1);
    }

  // 2. The explicit terms built only from values ACROSS the lines (they do not change during the
  // iteration): cross convection (PQ/h)_y, the cross-derivative dispersive terms of Psi (eq. 4),
  // and the cross part of the eddy-viscosity stress (eq. 6). Edges of the grid are walls: the
  // tangential flux there is 0 and eta is mirrored (clamped neighbour index).
  // The same face term serves the interior lines (neighbours l-1, l+1: contiguous, vectorised)
  // and the two edge lines of the grid (clamped neighbours, scalar).
  // Per-cell pieces of the cross terms, computed once per cell (each serves the faces on both
  // sides): corner depth sums, eta_yy, eta_y, Q_yt and eddy-viscosity sums.
  double* __restrict h_pair_north = s.h_pair_north.data();
  double* __restrict h_pair_south = s.h_pair_south.data();
  double* __restrict cell_eta_yy = s.cell_eta_yy.data();
  double* __restrict cell_eta_y = s.cell_eta_y.data();
  double* __restrict cell_flux_yt = s.cell_flux_yt.data();
  double* __restrict cell_slope_across = s.cell_slope_across.data();
  double* __restrict nu_pair_north = s.nu_pair_north.data();
  double* __restrict nu_pair_south = s.nu_pair_south.data();
  auto cell_terms = [&](auto extrapolates, int c, int j, int l, int ln, int ls) __attribute__((always_inline)) {
    const std::size_t i = c * stride + l, in_ = c * stride + ln, is = c * stride + ls;
    // A wall north or south of the cell is read as its mirror: the cell's own level and depth
    // (mark_dispersive), as the clamped index does at the grid's edges.
    const double e_here = eta_across(extrapolates, i);
    double e_north = eta_across(extrapolates, in_), e_south = eta_across(extrapolates, is);
    const double depth_i = depth[i];
    double depth_north = depth[in_], depth_south = depth[is];
    if constexpr (kMirrorWalls) {
      const double north_wall = mirror_north[c * W + j], south_wall = mirror_south[c * W + j];
      e_north += north_wall * (e_here - e_north);
      e_south += south_wall * (e_here - e_south);
      depth_north += north_wall * (depth_i - depth_north);
      depth_south += south_wall * (depth_i - depth_south);
    }
    const double h_here = std::max(depth_i + e_here, dry);
    h_pair_north[c * W + j] = h_here + std::max(depth_north + e_north, dry);
    h_pair_south[c * W + j] = h_here + std::max(depth_south + e_south, dry);
    cell_eta_yy[c * W + j] = (e_north - 2.0 * e_here + e_south) * inv_dy2;
    cell_eta_y[c * W + j] = (e_north - e_south) * 0.5 * inv_dy;
    // Bed slope across the lines (one-sided at the grid edges, 0 on a single line); the face takes
    // the mean of its two cells.
    // (The quotient is formed on every line and selected, so no division sits under a condition.)
    const double slope = (depth_north - depth_south) / ((ln == ls ? 1 : ln - ls) * dy);
    cell_slope_across[c * W + j] = ln == ls ? 0.0 : slope;
    cell_flux_yt[c * W + j] = (tangential_rate[c * tstride + l + 1] - tangential_rate[c * tstride + l]) * inv_dy;
    // The cross stress is explicit: its viscosity is capped for stability (nu dt/dy^2 <= 0.2);
    // the along-line stress is implicit and uses nu in full.
    if (kOpenWater) return;
    const double nu_i = std::min(static_cast<double>(nu[i]), nu_explicit_max);
    nu_pair_north[c * W + j] = nu_i + std::min(static_cast<double>(nu[in_]), nu_explicit_max);
    nu_pair_south[c * W + j] = nu_i + std::min(static_cast<double>(nu[is]), nu_explicit_max);
  };
  const int j_first = lb == 0 ? 1 : 0, j_last = le == rows ? n - 1 : n;
  with_constant(eta_extrapolates, [&](auto extrapolates) __attribute__((always_inline)) {
    for (int c = 0; c < cols; ++c) {
      #pragma GCC ivdep
      for (int j = j_first; j < j_last; ++j) cell_terms(extrapolates, c, j, lb + j, lb + j + 1, lb + j - 1);
      if (j_first == 1) cell_terms(extrapolates, c, 0, 0, std::min(1, rows - 1), 0);
      if (j_last == n - 1 && !(j_first == 1 && n == 1))
        cell_terms(extrapolates, c, n - 1, rows - 1, rows - 1, std::max(rows - 2, 0));
    }
  });

  auto fixed_face = [&](auto extrapolates, auto total_depth, auto fully_nonlinear, int f, int j, int l, int ln, int ls, double north,
                        double south) __attribute__((always_inline)) {
    const int L = f - 1, R = f;
    const std::size_t face = f * stride + l;
    auto c_at = [stride](int c, int line) { return c * stride + line; };
    auto t_at = [tstride](int c, int k2) { return c * tstride + k2; };
    const std::size_t cL = c_at(L, l), cR = c_at(R, l);
    const double n_f = kOpenWater ? 1.0 : face_porosity(porosity, inv_n, cL, cR), inv_n_f = kOpenWater ? 1.0 : 1.0 / n_f;
    const double d = face_depth(depth, cL, cR);
    // (PQ/h)_y at the face from the two corners north and south of it.
    const double h_north = 0.25 * (h_pair_north[L * W + j] + h_pair_north[R * W + j]);
    const double h_south = 0.25 * (h_pair_south[L * W + j] + h_pair_south[R * W + j]);
    const double corner_north = north * 0.25 * (tangential[t_at(L, l + 1)] + tangential[t_at(R, l + 1)]) *
                                (normal_across(face) + normal_across(f * stride + ln)) / h_north;
    const double corner_south = south * 0.25 * (tangential[t_at(L, l)] + tangential[t_at(R, l)]) *
                                (normal_across(face) + normal_across(f * stride + ls)) / h_south;
    double term = -inv_n_f * (corner_north - corner_south) * inv_dy;

    // Psi_x of seed 003 eq. (4) (Madsen & Sorensen 1992 eq. 12), the cross-derivative parts:
    //   -(B+1/3) d^2 Q_xyt - n B g d^3 eta_xyy - d d_x (Q_yt/6 + n B g d eta_yy) - d d_y (Q_xt/6 + n B g d eta_xy)
    // Mixed derivatives take each axis' own size: the per-cell y parts (eta_yy, eta_y, Q_yt, d_y)
    // are divided by dy above, their x differences here by dx.
    const double w = dispersion_weight[f * W + j];
    const double eta_yy_L = cell_eta_yy[L * W + j], eta_yy_R = cell_eta_yy[R * W + j];
    const double eta_y_L = cell_eta_y[L * W + j], eta_y_R = cell_eta_y[R * W + j];
    const double flux_yt_L = cell_flux_yt[L * W + j], flux_yt_R = cell_flux_yt[R * W + j];
    const double eta_xyy = (eta_yy_R - eta_yy_L) * inv_dx;
    const double eta_yy_face = 0.5 * (eta_yy_L + eta_yy_R);
    const double eta_xy = (eta_y_R - eta_y_L) * inv_dx;
    const double flux_xyt = (flux_yt_R - flux_yt_L) * inv_dx;
    const double flux_yt_face = 0.5 * (flux_yt_L + flux_yt_R);
    const double flux_xt = 0.5 * ((tangential_rate[t_at(R, l)] - tangential_rate[t_at(L, l)]) +
                                  (tangential_rate[t_at(R, l + 1)] - tangential_rate[t_at(L, l + 1)])) * inv_dx;
    const double slope_along = face_slope_along(depth, cL, cR, dx);
    const double slope_across = clamped(0.5 * (cell_slope_across[L * W + j] + cell_slope_across[R * W + j]),
                                        -kMaxDispersiveSlope, kMaxDispersiveSlope);
    // D: the depth of the dispersive terms, d (seed 003) or the total depth at t^{n+1/2}
    // (SweepConstants::dispersion_on_total_depth; docs/solver.md "Dispersion depth").
    double D = d;
    if constexpr (decltype(total_depth)::value)
      D = std::max(d + 0.5 * (eta_across(extrapolates, cL) + eta_across(extrapolates, cR)), dry);
    const double nBgd = n_f * B * g * D;
    const double psi = -B3 * D * D * flux_xyt - nBgd * D * D * eta_xyy -
                       D * slope_along * (flux_yt_face / 6.0 + nBgd * eta_yy_face) -
                       D * slope_across * (flux_xt / 6.0 + nBgd * eta_xy);
    term -= w * psi;
    // Equations::kFullyNonlinear: the fully nonlinear terms in the rate of the flux ACROSS the lines
    // (nonlinear_dispersion.hpp), with the across estimates the seed's -(B+1/3) d^2 Q_xyt uses: the
    // Serre term -(1/3) d/dx (h^3 d/dy (Q_t / h)) and the enhancement -B h^2 Q_xyt, less their
    // linearisation (h -> d).
    if constexpr (decltype(fully_nonlinear)::value) {
      const double e_L = eta_across(extrapolates, cL), e_R = eta_across(extrapolates, cR);
      const double h_face = std::max(d + 0.5 * (e_L + e_R), dry);
      const double weight = w * fully_nonlinear_weight(0.5 * (e_L + e_R), d, dry) * subcritical[face];
      const double h_L = std::max(static_cast<double>(depth[cL]) + e_L, dry), h_R = std::max(static_cast<double>(depth[cR]) + e_R, dry);
      const double dL = depth[cL], dR = depth[cR], dL3 = dL * dL * dL, dR3 = dR * dR * dR;
      const double rate_LN = tangential_rate[t_at(L, l + 1)], rate_LS = tangential_rate[t_at(L, l)];
      const double rate_RN = tangential_rate[t_at(R, l + 1)], rate_RS = tangential_rate[t_at(R, l)];
      // Total and still-water depths of the across faces north and south of L and R.
      const double h_LN = 0.5 * h_pair_north[L * W + j], h_LS = 0.5 * h_pair_south[L * W + j];
      const double h_RN = 0.5 * h_pair_north[R * W + j], h_RS = 0.5 * h_pair_south[R * W + j];
      const double d_LN = 0.5 * (dL + depth[c_at(L, ln)]), d_LS = 0.5 * (dL + depth[c_at(L, ls)]);
      const double d_RN = 0.5 * (dR + depth[c_at(R, ln)]), d_RS = 0.5 * (dR + depth[c_at(R, ls)]);
      // Where waves break each cell's share fades by 1 - B inside the derivative along the line
      // (conservation form; BreakingParameters::fade_fully_nonlinear_terms), the enhancement by the
      // face's mean.
      const double keep_L = 1.0 - breaking[cL], keep_R = 1.0 - breaking[cR];
      // (Written so that keep = 1 gives the unfaded expression bit for bit.)
      const double serre =
          -(inv_dx * inv_dy / 3.0) *
          (keep_R * h_R * h_R * h_R * (rate_RN / h_RN - rate_RS / h_RS) - keep_L * h_L * h_L * h_L * (rate_LN / h_LN - rate_LS / h_LS) -
           keep_R * dR3 * (rate_RN * linear_inverse_depth(d_RN, dry) - rate_RS * linear_inverse_depth(d_RS, dry)) +
           keep_L * dL3 * (rate_LN * linear_inverse_depth(d_LN, dry) - rate_LS * linear_inverse_depth(d_LS, dry)));
      const double enhancement = -0.5 * (keep_L + keep_R) * B * (h_face * h_face - d * d) * (rate_RN - rate_RS - rate_LN + rate_LS) * inv_dx * inv_dy;
      term -= weight * (serre + enhancement);
    }

    // F_x of seed 003 eq. (6), cross part: -(d/dy) nu (P_y + Q_x), divided by n. P_y + Q_x is
    // (dP dx/dy + dQ) / dx, so square cells (dx/dy = 1 exactly) keep the square scheme's bits.
    if (!kOpenWater) {
    const double nu_north = north * 0.25 * (nu_pair_north[L * W + j] + nu_pair_north[R * W + j]);
    const double nu_south = south * 0.25 * (nu_pair_south[L * W + j] + nu_pair_south[R * W + j]);
    const double stress_north = nu_north * ((normal_across(f * stride + ln) - normal_across(face)) * aspect +
                                            (tangential[t_at(R, l + 1)] - tangential[t_at(L, l + 1)])) * inv_dx;
    const double stress_south = nu_south * ((normal_across(face) - normal_across(f * stride + ls)) * aspect +
                                            (tangential[t_at(R, l)] - tangential[t_at(L, l)])) * inv_dx;
    term += inv_n_f * (stress_north - stress_south) * inv_dy;
    }
    fixed_term[f * W + j] = term;
    const double flux_t = 0.25 * (tangential[t_at(L, l)] + tangential[t_at(R, l)] + tangential[t_at(L, l + 1)] + tangential[t_at(R, l + 1)]);
    tangential_squared[f * W + j] = flux_t * flux_t;
  };
  // eta^{n+1/2} enters the fixed terms only through the total depth: one instance without it.
  auto fixed_faces = [&](auto extrapolates, auto total_depth, auto fn) __attribute__((always_inline)) {
    for (int f = 1; f < cols; ++f) {
      #pragma GCC ivdep
      for (int j = j_first; j < j_last; ++j)
        fixed_face(extrapolates, total_depth, fn, f, j, lb + j, lb + j + 1, lb + j - 1, 1.0, 1.0);
      if (j_first == 1) fixed_face(extrapolates, total_depth, fn, f, 0, 0, std::min(1, rows - 1), 0, rows > 1 ? 1.0 : 0.0, 0.0);
      if (j_last == n - 1 && !(j_first == 1 && n == 1))
        fixed_face(extrapolates, total_depth, fn, f, n - 1, rows - 1, rows - 1, std::max(rows - 2, 0), 0.0,
                   rows > 1 ? 1.0 : 0.0);
    }
  };
  if (total_depth_dispersion)
    with_constant(eta_extrapolates, [&](auto extrapolates) __attribute__((always_inline)) {
      fixed_faces(extrapolates, std::true_type{}, std::false_type{});
    });
  else if (fully_nonlinear_along)
    with_constant(eta_extrapolates, [&](auto extrapolates) __attribute__((always_inline)) {
      fixed_faces(extrapolates, std::false_type{}, std::true_type{});
    });
  else
    fixed_faces(std::false_type{}, std::false_type{}, std::false_type{});
  // The fully nonlinear remainder (explicit, on the left side like Psi: subtracted).
  if (const float* __restrict force = in.explicit_force)
    for (int f = 1; f < cols; ++f)
      #pragma GCC ivdep
      for (int j = 0; j < n; ++j) fixed_term[f * W + j] -= static_cast<double>(force[f * stride + lb + j]);

  // 3. Iterate the time-centred terms that depend on the lines' own unknowns.
  // seed 003 eq. (1): n (eta - E)/dt = -(1/2) d(increment)/dx  (the Crank-Nicolson half of the new flux)
  auto eta_from_increment = [&](int c, int j) __attribute__((always_inline)) {
    const std::size_t i = c * stride + lb + j;
    return eta_base[i] - 0.5 * dt * inv_dx * inv_n[i] * (increment[(c + 1) * W + j] - increment[c * W + j]);
  };
  const int iterations = std::max(1, k.iterations);
  for (int iteration = 0; iteration < iterations; ++iteration) {
    // eta at t^{n+1/2} from this iterate (eq. 1 and the time average in one pass).
    for (int c = 0; c < cols; ++c)
      #pragma GCC ivdep
      for (int j = 0; j < n; ++j) {
        eta_half[c * W + j] = 0.5 * (eta_old[c * stride + lb + j] + eta_from_increment(c, j));
      }
    // Beyond the ends of the line the grid edge is a wall: mirror ghost cells (-1 -> 0, -2 -> 1).
    #pragma GCC ivdep
    for (int j = 0; j < n; ++j) {
      eta_half[-1 * W + j] = eta_half[0 * W + j];
      eta_half[-2 * W + j] = eta_half[std::min(1, cols - 1) * W + j];
      eta_half[cols * W + j] = eta_half[(cols - 1) * W + j];
      eta_half[(cols + 1) * W + j] = eta_half[std::max(cols - 2, 0) * W + j];
    }
    // Momentum flux P^2/h through the cell centre, momentum-conservative first-order upwind
    // (Stelling & Duinmeijer 2003): the mean mass flux q of the cell times the velocity P/h of
    // the upwind face. Central differences here let bores in the surf zone and run-up blow up.
    for (int f = 0; f < faces; ++f)
      #pragma GCC ivdep
      for (int j = 0; j < n; ++j) {
        const double h_face = std::max(depth_at_face(f, f * stride + lb + j) + 0.5 * (eta_half[(f - 1) * W + j] + eta_half[f * W + j]), dry);
        const double flux_f = normal_old[f * stride + lb + j] + 0.5 * increment[f * W + j];
        flux_half[f * W + j] = flux_f;
        face_velocity[f * W + j] = flux_f / h_face;
      }
    // The edge faces of an imposed current (SweepConstants::edges_hold_flux) carry u d: their depth
    // is their one cell's (the ghost beyond it mirrors its level), not a wall's 0.
    edge_face_velocities(depth, eta_half, flux_half, face_velocity, cols, stride, lb, n, dry, k.edges_hold_flux);
    // Upwinding is first order: applied everywhere it damps non-breaking waves ~20 % over the
    // Berkhoff shoal. So it is blended in by the local Froude number Fr = |u| / sqrt(g h): central
    // (second order, no numerical dissipation) below Fr = 0.2, where non-breaking waves live (linear
    // waves have Fr = a/h, < 0.15 on the Berkhoff shoal), fully upwind above Fr = 0.4 (bores,
    // run-up tongues), linear in between so the switch itself makes no noise.
    for (int c = 0; c < cols; ++c)
      #pragma GCC ivdep
      for (int j = 0; j < n; ++j) {
        const double flux_c = 0.5 * (flux_half[c * W + j] + flux_half[(c + 1) * W + j]);
        const double u_west = face_velocity[c * W + j], u_east = face_velocity[(c + 1) * W + j];
        const double u_upwind = flux_c > 0.0 ? u_west : u_east, u_central = 0.5 * (u_west + u_east);
        const double h_cell = std::max(depth[c * stride + lb + j] + eta_half[c * W + j], dry);
        const double froude2 = std::max(u_west * u_west, u_east * u_east) / (g * h_cell);
        const double upwind_weight = std::clamp((froude2 - 0.04) / (0.16 - 0.04), 0.0, 1.0);
        cell_term[c * W + j] = flux_c * (u_central + upwind_weight * (u_upwind - u_central));
      }

    // The tridiagonal rows are assembled and eliminated in one pass (the forward half of the
    // double sweep below): each row is used the moment it is built. Row 0 (the west grid edge) is
    // the identity with right side -P_old (a wall: flux 0), already in eliminated form.
    #pragma GCC ivdep
    for (int j = 0; j < n; ++j) {
      upper[j] = 0.0;
      right[j] = -normal_old[lb + j] * edge_release_factor;
    }
    with_constant(fully_nonlinear_along, [&](auto fully_nonlinear) __attribute__((always_inline)) {
    with_constant(total_depth_dispersion, [&](auto total_depth) __attribute__((always_inline)) {
      for (int f = 1; f < cols; ++f) {
        const int L = f - 1, R = f;
        const int cell_before = std::max(f - 2, 0), cell_after = std::min(f + 1, cols - 1);  // fully nonlinear terms
        #pragma GCC ivdep
        for (int j = 0; j < n; ++j) {
          const std::size_t face = f * stride + lb + j, cL = L * stride + lb + j, cR = R * stride + lb + j;
          const double n_f = kOpenWater ? 1.0 : face_porosity(porosity, inv_n, cL, cR), inv_n_f = kOpenWater ? 1.0 : 1.0 / n_f;
          const double d = face_depth(depth, cL, cR);
          const double e_L = eta_half[L * W + j], e_R = eta_half[R * W + j];
          // Total depth at the face, never below dry_depth_m: the water above the higher bed governs a
          // face next to a dry cell (flooding); between two wet cells the mean is the second-order
          // value (SolverParameters::face_depth; the larger of the two everywhere adds
          // g |eta_x| eta_x dx / 2, a spurious amplitude dispersion: docs/solver.md "Face depth").
          const float depth_L = depth[cL], depth_R = depth[cR];
          const double h_mean = d + 0.5 * (e_L + e_R), h_above_bed = std::max(e_L, e_R) + std::min(depth_L, depth_R);
          const bool use_mean = (static_cast<double>(depth_L) + e_L > mean_face_wet_depth) &
                                (static_cast<double>(depth_R) + e_R > mean_face_wet_depth);
          const double h_f = std::max(use_mean ? h_mean : std::max(h_mean, h_above_bed), dry);
          const double inv_h_f = 1.0 / h_f;

          // Along-line explicit terms: convection (P^2/h)_x / n and the along parts of Psi_x:
          //   -n B g d^3 eta_xxx - d d_x n B g d 2 eta_xx   (time-centred, iterated)
          const double w = dispersion_weight[f * W + j];
          // A wall before L or after R is read as its mirror (mark_dispersive), as the ghost cells at
          // the grid's edges are.
          double e_m2 = eta_half[(f - 2) * W + j], e_p1 = eta_half[(f + 1) * W + j];
          if constexpr (kMirrorWalls) {
            e_m2 += mirror_before[f * W + j] * (e_L - e_m2);
            e_p1 += mirror_after[f * W + j] * (e_R - e_p1);
          }
          const double eta_xxx = (e_p1 - 3.0 * e_R + 3.0 * e_L - e_m2) * inv_dx3;
          const double eta_xx = 0.5 * (e_p1 - e_R - e_L + e_m2) * inv_dx2;
          const double slope_along = face_slope_along(depth, cL, cR, dx);
          // D: the depth of the dispersive terms (d, or h_mean with dispersion_on_total_depth).
          double D = d;
        if constexpr (decltype(total_depth)::value) D = std::max(h_mean, dry);
          const double along = -inv_n_f * (cell_term[R * W + j] - cell_term[L * W + j]) * inv_dx +
                               w * n_f * B * g * D * D * (D * eta_xxx + 2.0 * slope_along * eta_xx);
          // Implicit parts of Psi_x: -(B+1/3) D^2 P_xxt - (1/3) D d_x P_xt
          const double D2 = w * B3 * D * D * inv_dx2;
          const double S1 = w * D * slope_along * inv_dx / 6.0;
          // Equations::kFullyNonlinear: the along-line flux-rate part of the fully nonlinear terms,
          // implicit (nonlinear_dispersion.hpp): the Serre term -(1/3) d/dx (h^3 d/dx (P_t / h)) and
          // the enhancement -B h^2 P_xxt, minus the same with h -> d (the seed's terms above hold the
          // linear part). Cells L, R and faces f-1, f, f+1 at t^{n+1/2}, from this iterate.
          double fn_lower = 0.0, fn_diagonal = 0.0, fn_upper = 0.0;
          if constexpr (decltype(fully_nonlinear)::value) {
            const double weight = w * fully_nonlinear_weight(0.5 * (e_L + e_R), d, dry) * subcritical[face];
            // The faces f-1 and f+1 from their cells; at a wall (f-1 = 0, f+1 = cols) the coefficient
            // is 0 below, and the clamped cell index only keeps the load inside the array (the
            // index depends on f alone, so the loop over the lines stays free of conditions).
            const double d_before = 0.5 * (static_cast<double>(depth[static_cast<std::size_t>(cell_before) * stride + lb + j]) + depth_L);
            const double d_after = 0.5 * (static_cast<double>(depth[static_cast<std::size_t>(cell_after) * stride + lb + j]) + depth_R);
            const double h_L = std::max(static_cast<double>(depth_L) + e_L, dry), h_R = std::max(static_cast<double>(depth_R) + e_R, dry);
            const double h_before = std::max(d_before + 0.5 * (e_m2 + e_L), dry), h_here = std::max(h_mean, dry),
                         h_after = std::max(d_after + 0.5 * (e_R + e_p1), dry);
            const double dL3 = static_cast<double>(depth_L) * depth_L * depth_L, dR3 = static_cast<double>(depth_R) * depth_R * depth_R;
            const double third = inv_dx2 / 3.0, enhancement = B * (h_here * h_here - d * d) * inv_dx2;
            // A wall face (the grid edge) carries no flux: nothing couples to it.
            const double inside_before = f > 1 ? 1.0 : 0.0, inside_after = f + 1 < cols ? 1.0 : 0.0;
            // Where waves break, cell L's and R's shares of h^3 d/dx(P_t/h) fade by 1 - B inside the
            // outer derivative (conservation form), the enhancement by the face's mean.
            const double keep_L = 1.0 - breaking[cL], keep_R = 1.0 - breaking[cR], keep_face = 0.5 * (keep_L + keep_R);
            fn_lower = inside_before * weight * (-third * keep_L * (h_L * h_L * h_L / h_before - dL3 * linear_inverse_depth(d_before, dry)) -
                                                 keep_face * enhancement);
            fn_upper = inside_after * weight * (-third * keep_R * (h_R * h_R * h_R / h_after - dR3 * linear_inverse_depth(d_after, dry)) -
                                                keep_face * enhancement);
            // (Written so that keep = 1 gives the unfaded expression bit for bit.)
            fn_diagonal = weight * (third * ((keep_L * h_L * h_L * h_L + keep_R * h_R * h_R * h_R) / h_here -
                                             (keep_L * dL3 + keep_R * dR3) * linear_inverse_depth(d, dry)) +
                                    2.0 * keep_face * enhancement);
          }

          // Bed friction: the larger of the Chezy stress g P |(P,Q)| / (h^2 C^2) and the laminar
          // film's Poiseuille stress 3 nu P / h^2 (docs/solver.md, "Bed friction"), and the porous
          // resistance n P (alpha + beta |(P,Q)|/h) of eq. (2), divided by n, implicit (backward
          // Euler) so any resistance stays stable.
          const double flux_f = flux_half[f * W + j];  // |(P, Q)|; sqrt vectorises (-fno-math-errno)
          const double flux_magnitude = std::sqrt(flux_f * flux_f + tangential_squared[f * W + j]);
          const double friction =
              std::max(g * flux_magnitude * inverse_chezy2, laminar_film_factor) * inv_n_f * inv_h_f * inv_h_f;
          double resistance = friction;
          if (!kOpenWater) {
            const double n3 = n_f * n_f * n_f;  // laminar alpha (1/s) and turbulent beta (1/m) of eq. (2)
            const double D_f = stone_diameter * face_stone_diameter_ratio(porosity, stone_ratio, cL, cR);
            const double alpha = laminar_factor * (1.0 - n_f) * (1.0 - n_f) / (n3 * D_f * D_f);
            const double beta = turbulent_factor * (1.0 - n_f) / (n3 * D_f);
            resistance = friction + n_f * (alpha + beta * flux_magnitude * inv_h_f);
          }

          // Gravity n g h eta_x at t^{n+1/2} with eta* = E - dt/(2 n dx) d(increment): couples three faces.
          const double G = n_f * g * h_f * dt * dt * inv_dx2 * 0.25;
          // Eddy viscosity along the line, (1/n) d/dx (nu dP/dx), Crank-Nicolson.
          const double V_L = kOpenWater ? 0.0 : 0.5 * dt * nu[cL] * inv_n_f * inv_dx2;
          const double V_R = kOpenWater ? 0.0 : 0.5 * dt * nu[cR] * inv_n_f * inv_dx2;

          const double gravity = -dt * n_f * g * h_f * 0.5 * inv_dx * (eta_base[cR] - eta_base[cL] + eta_old[cR] - eta_old[cL]);
          const double old_f = normal_old[face];
          const double eddy_old =
              kOpenWater ? 0.0 : 2.0 * (V_R * (normal_old[face + stride] - old_f) - V_L * (old_f - normal_old[face - stride]));
          // Inactive faces get the identity row (flux to 0), selected arithmetically so the loop
          // has no branch and vectorises.
          const double on = active[f * W + j];  // 1 or 0: blended arithmetically, no branch
          const double lower_f = -D2 + S1 - G * inv_n[cL] - V_L + fn_lower, upper_f = -D2 - S1 - G * inv_n[cR] - V_R + fn_upper;
          const double diagonal_f = 1.0 + 2.0 * D2 + G * (inv_n[cL] + inv_n[cR]) + V_L + V_R + resistance * dt + fn_diagonal;
          const double right_f = gravity + dt * (fixed_term[f * W + j] + along) - resistance * dt * old_f + eddy_old;
          const double row_lower = on * lower_f, row_upper = on * upper_f;
          const double row_diagonal = on * diagonal_f + (1.0 - on), row_right = on * right_f - (1.0 - on) * old_f;
          // Double sweep (Thomas algorithm), forward elimination, all lines of the block in lock-step.
          // The systems are diagonally dominant (docs/solver.md), so no pivoting is needed.
          const double inverse_pivot = 1.0 / (row_diagonal - row_lower * upper[(f - 1) * W + j]);
          upper[f * W + j] = row_upper * inverse_pivot;
          right[f * W + j] = (row_right - row_lower * right[(f - 1) * W + j]) * inverse_pivot;
        }
      }
    });
    });
    #pragma GCC ivdep
    for (int j = 0; j < n; ++j) {  // row `cols`, the east grid edge: identity, flux 0 (or held)
      upper[cols * W + j] = 0.0;
      right[cols * W + j] = -normal_old[cols * stride + lb + j] * edge_release_factor;
    }
    #pragma GCC ivdep
    for (int j = 0; j < n; ++j) increment[(faces - 1) * W + j] = right[(faces - 1) * W + j];
    for (int f = faces - 2; f >= 0; --f)
      #pragma GCC ivdep
      for (int j = 0; j < n; ++j) increment[f * W + j] = right[f * W + j] - upper[f * W + j] * increment[(f + 1) * W + j];
  }
  // Thin-film guard of the moving shoreline: the flux of a face may not exceed a Froude number of
  // kMaxFroude (|P| <= Fr h sqrt(g h)). Only thin swash and backwash layers ever reach it; without
  // it their velocities P/h grow without bound as h -> dry_depth_m. Applied to the increment before
  // eta is computed from it, so mass stays conserved.
  for (int f = 1; f < cols; ++f)
    #pragma GCC ivdep
    for (int j = 0; j < n; ++j) {
      const double h_face = std::max(face_depth(depth, (f - 1) * stride + lb + j, f * stride + lb + j) +
                                         0.5 * (eta_half[(f - 1) * W + j] + eta_half[f * W + j]), dry);
      const double limit = kMaxFroude * h_face * std::sqrt(g * h_face);
      const double old_f = normal_old[f * stride + lb + j];
      const double flux_new = clamped(old_f + increment[f * W + j], -limit, limit);
      increment[f * W + j] = flux_new - old_f;
    }
  const std::size_t eta_cell_stride = out.eta_cell_stride, eta_line_stride = out.eta_line_stride;
  for (int c = 0; c < cols; ++c)
    #pragma GCC ivdep
    for (int j = 0; j < n; ++j) eta_new[c * eta_cell_stride + (lb + j) * eta_line_stride] = eta_from_increment(c, j);
  for (int f = 0; f < faces; ++f)
    #pragma GCC ivdep
    for (int j = 0; j < n; ++j) normal_new[f * stride + lb + j] = normal_old[f * stride + lb + j] + increment[f * W + j];
}

// One sweep_block per kind of block, the walls' reading fixed (kMirrorWalls). Each kind of wall
// reading has its own function, compiled per instruction set like the sweep (GCC function
// multi-versioning, below): with both inlined into one function GCC 12 stops with an internal error.
template <bool kMirrorWalls>
__attribute__((always_inline)) inline void sweep_any_block(const StaticFrame& frame, const SweepConstants& constants,
                                                            const SweepInput& input, const SweepOutput& output,
                                                            const int line_begin, const int line_end, SweepScratch& scratch) {
  const bool open_water = !input.viscous && !frame.block_is_porous[static_cast<std::size_t>(line_begin / kBlockLines)];
  if (line_end - line_begin == kBlockLines) {
    if (open_water)
      sweep_block<true, true, kMirrorWalls>(frame, constants, input, output, line_begin, line_end, scratch);
    else
      sweep_block<true, false, kMirrorWalls>(frame, constants, input, output, line_begin, line_end, scratch);
  } else {
    if (open_water)
      sweep_block<false, true, kMirrorWalls>(frame, constants, input, output, line_begin, line_end, scratch);
    else
      sweep_block<false, false, kMirrorWalls>(frame, constants, input, output, line_begin, line_end, scratch);
  }
}

__attribute__((target_clones("default", "arch=x86-64-v3", "arch=x86-64-v4")))
void sweep_lines_mirroring_walls(const StaticFrame& frame, const SweepConstants& constants, const SweepInput& input,
                                 const SweepOutput& output, const int line_begin, const int line_end, SweepScratch& scratch) {
  sweep_any_block<true>(frame, constants, input, output, line_begin, line_end, scratch);
}

}  // namespace

// Compiled for three instruction sets and chosen once at load time by the CPU (GCC function
// multi-versioning): generic x86-64 (SSE2, 2 doubles per vector), x86-64-v3 (AVX2, 4) and
// x86-64-v4 (AVX-512, 8). The sweep is ~80 % of a step and vectorises over the block's lines.
// boussinesq_sweep.cpp is built with -ffp-contract=off (bake/CMakeLists.txt): no clone fuses a
// multiply and an add, so every clone rounds exactly as the generic code and a bake gives the
// same bits on any x86-64 CPU.
__attribute__((target_clones("default", "arch=x86-64-v3", "arch=x86-64-v4")))
void sweep_lines(const StaticFrame& frame, const SweepConstants& constants, const SweepInput& input,
                 const SweepOutput& output, const int line_begin, const int line_end, SweepScratch& scratch) {
  if (constants.mirror_walls)
    sweep_lines_mirroring_walls(frame, constants, input, output, line_begin, line_end, scratch);
  else
    sweep_any_block<false>(frame, constants, input, output, line_begin, line_end, scratch);
}

namespace {

constexpr int kTransposeTile = 32;

// 4 x 4 blocks of doubles are transposed in registers (GCC vector extensions: two shuffle stages),
// so both the loads (a row's 4 values) and the stores (a column's 4 values) are whole vectors.
using Quad = double __attribute__((vector_size(32)));
using QuadMask = long long __attribute__((vector_size(32)));

// By reference, not by value: a 32-byte vector passed by value changes the ABI between clones.
__attribute__((always_inline)) inline void load_quad(Quad& v, const double* p) { std::memcpy(&v, p, sizeof v); }
__attribute__((always_inline)) inline void store_quad(double* p, const Quad& v) { std::memcpy(p, &v, sizeof v); }

// rows[i] = row i of a 4 x 4 block; afterwards rows[j] holds column j.
__attribute__((always_inline)) inline void transpose_quads(Quad rows[4]) {
  const Quad t0 = __builtin_shuffle(rows[0], rows[1], QuadMask{0, 4, 2, 6});
  const Quad t1 = __builtin_shuffle(rows[0], rows[1], QuadMask{1, 5, 3, 7});
  const Quad t2 = __builtin_shuffle(rows[2], rows[3], QuadMask{0, 4, 2, 6});
  const Quad t3 = __builtin_shuffle(rows[2], rows[3], QuadMask{1, 5, 3, 7});
  rows[0] = __builtin_shuffle(t0, t2, QuadMask{0, 1, 4, 5});
  rows[1] = __builtin_shuffle(t1, t3, QuadMask{0, 1, 4, 5});
  rows[2] = __builtin_shuffle(t0, t2, QuadMask{2, 3, 6, 7});
  rows[3] = __builtin_shuffle(t1, t3, QuadMask{2, 3, 6, 7});
}

// Walks rows [r0, r1) of a cols x rows -> rows x cols transpose tile by tile (kTransposeTile squared
// stays in the L1 cache), 4 x 4 blocks in registers, the ragged edges element by element.
// `element(i, o)` moves input element i to output position o; `block(in_offsets, out_offsets)` does
// the same for a 4 x 4 block (row r of the block starts at in_offsets[r], column c at out_offsets[c]).
template <class Element, class Block>
__attribute__((always_inline)) inline void walk_transpose(int cols, int rows, int r0, int r1, const Element& element,
                                                          const Block& block) {
  for (int c0 = 0; c0 < cols; c0 += kTransposeTile) {
    const int c1 = std::min(cols, c0 + kTransposeTile);
    int r = r0;
    for (; r + 4 <= r1; r += 4) {
      int c = c0;
      for (; c + 4 <= c1; c += 4) {
        std::size_t in_offsets[4], out_offsets[4];
        for (int k = 0; k < 4; ++k) {
          in_offsets[k] = static_cast<std::size_t>(r + k) * cols + c;
          out_offsets[k] = static_cast<std::size_t>(c + k) * rows + r;
        }
        block(in_offsets, out_offsets);
      }
      for (; c < c1; ++c)
        for (int k = 0; k < 4; ++k)
          element(static_cast<std::size_t>(r + k) * cols + c, static_cast<std::size_t>(c) * rows + r + k);
    }
    for (; r < r1; ++r)
      for (int c = c0; c < c1; ++c) element(static_cast<std::size_t>(r) * cols + c, static_cast<std::size_t>(c) * rows + r);
  }
}

// Cloned per instruction set like the sweep (AVX2 and AVX-512 do a Quad in one register).
__attribute__((target_clones("default", "arch=x86-64-v3", "arch=x86-64-v4")))
void transpose_rows(const double* __restrict in, double* __restrict out, int cols, int rows, int r0, int r1) {
  walk_transpose(
      cols, rows, r0, r1, [&](std::size_t i, std::size_t o) { out[o] = in[i]; },
      [&](const std::size_t* in_offsets, const std::size_t* out_offsets) {
        Quad block[4];
        for (int k = 0; k < 4; ++k) load_quad(block[k], in + in_offsets[k]);
        transpose_quads(block);
        for (int k = 0; k < 4; ++k) store_quad(out + out_offsets[k], block[k]);
      });
}

// Float arrays (the eddy viscosity while cells break, the static depths once): element by element
// within the cache-sized tiles; not cloned, it is a small part of a step.
void transpose_float_rows(const float* __restrict in, float* __restrict out, int cols, int rows, int r0, int r1) {
  auto element = [&](std::size_t i, std::size_t o) { out[o] = in[i]; };
  walk_transpose(cols, rows, r0, r1, element, [&](const std::size_t* in_offsets, const std::size_t* out_offsets) {
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) out[out_offsets[c] + r] = in[in_offsets[r] + c];
  });
}

// The same walk for the across flux at t^{n+1/2} and its rate (HalfAndRate in boussinesq_sweep.hpp);
// the arithmetic is element-wise, so the blocks give the same bits as the single elements.
__attribute__((target_clones("default", "arch=x86-64-v3", "arch=x86-64-v4")))
void half_and_rate_rows(HalfAndRate kind, const double* __restrict old_flux, const double* __restrict other, double dt,
                        double* __restrict half, double* __restrict rate, int cols, int rows, int r0, int r1) {
  auto transform = [&](auto old_value, auto other_value, auto& half_value, auto& rate_value) {
    if (kind == HalfAndRate::kFromNewFlux) {
      half_value = 0.5 * (old_value + other_value);
      rate_value = (other_value - old_value) / dt;
    } else {
      const auto increment = kind == HalfAndRate::kFromIncrement ? other_value : other_value - old_value;
      half_value = old_value + 0.5 * increment;
      rate_value = increment / dt;
    }
  };
  walk_transpose(
      cols, rows, r0, r1, [&](std::size_t i, std::size_t o) { transform(old_flux[i], other[i], half[o], rate[o]); },
      [&](const std::size_t* in_offsets, const std::size_t* out_offsets) {
        Quad half_block[4], rate_block[4];
        for (int k = 0; k < 4; ++k) {
          Quad old_values, other_values;
          load_quad(old_values, old_flux + in_offsets[k]);
          load_quad(other_values, other + in_offsets[k]);
          transform(old_values, other_values, half_block[k], rate_block[k]);
        }
        transpose_quads(half_block);
        transpose_quads(rate_block);
        for (int k = 0; k < 4; ++k) {
          store_quad(half + out_offsets[k], half_block[k]);
          store_quad(rate + out_offsets[k], rate_block[k]);
        }
      });
}

}  // namespace

void transpose(const double* in, double* out, int cols, int rows) {
  tbb::parallel_for(0, (rows + kTransposeTile - 1) / kTransposeTile, [&](int block) {
    transpose_rows(in, out, cols, rows, block * kTransposeTile, std::min(rows, (block + 1) * kTransposeTile));
  });
}

void transpose(const float* in, float* out, int cols, int rows) {
  tbb::parallel_for(0, (rows + kTransposeTile - 1) / kTransposeTile, [&](int block) {
    transpose_float_rows(in, out, cols, rows, block * kTransposeTile, std::min(rows, (block + 1) * kTransposeTile));
  });
}

void transpose_half_and_rate(HalfAndRate kind, const double* old_flux, const double* other, double time_step_s,
                             double* half, double* rate, int cols, int rows) {
  tbb::parallel_for(0, (rows + kTransposeTile - 1) / kTransposeTile, [&](int block) {
    half_and_rate_rows(kind, old_flux, other, time_step_s, half, rate, cols, rows, block * kTransposeTile,
                       std::min(rows, (block + 1) * kTransposeTile));
  });
}

}  // namespace nearshore::boussinesq::detail
