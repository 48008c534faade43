#pragma once
// The two-dimensional shallow-water equations (seed 000 eq. 4.7-4.9) solved by the second-order
// central-upwind scheme of Kurganov & Petrova (2007, "A second-order well-balanced positivity
// preserving central-upwind scheme for the Saint-Venant system", Commun. Math. Sci. 5, 133-160),
// the flux of seed 000 eq. 4.10-4.15:
//
//   U = (w, hu, hv), w = h + B (surface elevation, z up), B the bottom elevation (-depth)
//   dU/dt = -(H^x_{i+1/2,j} - H^x_{i-1/2,j}) / dx - (H^y_{i,j+1/2} - H^y_{i,j-1/2}) / dy + S_ij
//
// 1. B is given at cell corners (piecewise bilinear); interface values are the means of their two
//    corners, the cell value the mean of its four interface values (KP eq. 3.2-3.4).
// 2. Piecewise-linear reconstruction of w, hu, hv with the generalised minmod limiter
//    (theta = 1.3) and KP's positivity correction: where the reconstructed w at an interface falls
//    below B there, the slope is changed so that h = 0 at that interface (KP section 3.1).
// 3. Velocities at the interfaces desingularised as in seed 000 eq. 4.14-4.15 (KP eq. 2.17):
//    u = sqrt(2) h (hu) / sqrt(h^4 + max(h^4, eps)), eps = h_eps^4, and hu recomputed as h u.
// 4. Local speeds a+- (eq. 4.12-4.13) and the central-upwind flux (eq. 4.11):
//    H = (a+ F(U^E) - a- F(U^W)) / (a+ - a-) + a+ a- / (a+ - a-) (U^W - U^E),
//    F = (hu, hu u + g h^2 / 2, hu v).
// 5. The well-balanced source S = (0, -g hbar^x (B_{i+1/2} - B_{i-1/2}) / dx, -g hbar^y (...) / dy),
//    hbar the mean of the two reconstructed interface depths of the cell (KP eq. 3.11): a lake at
//    rest (w constant, u = v = 0) is an exact discrete steady state.
// 6. Time: the second-order strong-stability-preserving Runge-Kutta (Heun) method; each stage is a
//    forward-Euler step under dt <= cfl min(dx / a^x, dy / a^y) with cfl = 0.25, which keeps the
//    cell depths non-negative (KP theorem 3.1).
//
// A pressure head on the surface (a floating hull's displacement, zeta = p / (rho g), m) enters
// exactly like a raised bottom in the momentum equations (-g h grad(B + zeta)), so the scheme runs
// on B' = B + zeta for the reconstruction, the fluxes and the source, with w' = w + zeta; mass still
// moves with h. A hull at rest over its depression is then an exact steady state too.
//
// Edges: two ghost layers; kWall reflects (mirror, normal discharge negated), kOpen passes waves
// out (mirror with the discharge kept: zero gradient); the bow-wave grid adds absorbing layers.
//
// Cost (docs/ships.md, `nearshore bench ships`): one stage is a single sweep over the rows. Each
// row is reconstructed in x and in y into row buffers (w' = w + zeta made one row ahead into a
// ring), its x fluxes and the y fluxes across its southern faces are computed from them, the
// rates are accumulated in two row buffers, and a row takes its Euler stage as soon as its rates
// are complete. A stage so reads the state and the bottom once and writes the new state once,
// with no full-grid rate or w' arrays. The loops are branch-free (minmod as max/min, the
// positivity correction and the desingularisation as selects) so that the compiler vectorises
// them; they are built for AVX-512, AVX2 and the baseline, chosen at load time. Subnormal numbers
// are flushed to zero while a step runs (the caller's mode is restored): a wave's far field decays
// into them, and each costs a microcode assist; only values below 1.2e-38 (float) change.
//
// Precision. The scheme is written once for a scalar type. `ShallowWaterGrid` (double) is the
// reference: its well-balanced states hold to 1e-15. `BowWaveGrid` (float) is what bow waves
// run on: their heights are uploaded as float anyway, and the errors of their forcing (a
// splatted, smoothed pressure, a whole-cell window) are centimetres, while float round-off on a
// 10 m deep grid is 1e-6 m; the physics tests run on both types with the round-off of each.
#include <cstddef>
#include <vector>

namespace nearshore::ships {

enum class EdgeKind { kWall, kOpen };

struct ShallowWaterOptions {
  double gravity_m_s2 = 9.81;
  double cfl = 0.25;                   ///< KP's positivity bound for 2-D forward-Euler stages
  double limiter_theta = 1.3;          ///< generalised minmod, in [1, 2]
  double desingularisation_depth_m = 0.01;  ///< h_eps of step 3 (KP use eps = dx^4)
};

template <class Real>
class BasicShallowWaterGrid {
 public:
  using Scalar = Real;
  /// columns x rows cells of spacing_m, cell (i, j) centred at ((i + 0.5) dx, (j + 0.5) dx) of
  /// the grid's own frame; flat bottom at elevation 0 and w = 0 (dry) until set.
  BasicShallowWaterGrid(int columns, int rows, double spacing_m, EdgeKind edges, ShallowWaterOptions options = {});

  int columns() const { return columns_; }
  int rows() const { return rows_; }
  double spacing_m() const { return spacing_m_; }
  const ShallowWaterOptions& options() const { return options_; }

  /// Bottom elevation (m, z up: -depth) at corner (i, j), i in [0, columns], j in [0, rows].
  void set_bottom_corner(int i, int j, double elevation_m);
  double bottom_corner(int i, int j) const;
  /// Cell-average bottom (the mean of its four interface values).
  double bottom_cell(int i, int j) const;
  /// Pressure head zeta (m) at corner (i, j): see above. 0 by default.
  void set_pressure_head_corner(int i, int j, double head_m);
  double pressure_head_corner(int i, int j) const;
  double pressure_head_cell(int i, int j) const;
  /// Call after changing bottoms or heads: recomputes the interface and cell values.
  void update_bottom();

  /// Cell state: surface elevation w (m), discharges hu, hv (m^2/s). Depth h = w - B_cell.
  Real& surface_m(int i, int j) { return w_[padded(i, j)]; }
  Real surface_m(int i, int j) const { return w_[padded(i, j)]; }
  Real& discharge_x_m2_s(int i, int j) { return hu_[padded(i, j)]; }
  Real& discharge_y_m2_s(int i, int j) { return hv_[padded(i, j)]; }
  Real discharge_x_m2_s(int i, int j) const { return hu_[padded(i, j)]; }
  Real discharge_y_m2_s(int i, int j) const { return hv_[padded(i, j)]; }
  Real depth_m(int i, int j) const { return w_[padded(i, j)] - b_cell_[padded(i, j)]; }

  /// Sum of h dx^2 over the cells (m^3).
  double total_volume_m3() const;
  /// The largest stable step for the current state (s): cfl dx / max(|u| + sqrt(g h)).
  double stable_time_step_s() const;
  /// Advances by dt_s in as many SSP-RK2 steps as the CFL condition needs; returns their number.
  /// Throws nearshore::Error (an internal error: every input that could cause it is range-checked)
  /// when that would take more than kMaxStepsPerAdvance steps or the wave speed is not finite,
  /// instead of hanging: a bow wave's frame takes 2-4 steps, the tests' longest runs under 1000.
  int advance(double dt_s);
  static constexpr int kMaxStepsPerAdvance = 20000;
  /// One SSP-RK2 step of exactly dt_s (the caller keeps it under the CFL limit).
  void step(double dt_s);

  /// The most negative cell depth any stage produced before the round-off clamp to 0 (m; 0 when
  /// none was negative). The scheme guarantees h >= 0; this shows it did.
  double most_negative_depth_m() const { return most_negative_depth_m_; }

  /// Moves the grid's content by (di, dj) whole cells (content at (i, j) goes to (i - di, j - dj):
  /// the grid's window moved di cells east, dj north); cells entering the window are left at
  /// w = 0, no discharge; the caller sets their bottom and calls update_bottom, then rest_new_cells.
  void shift_window(int di, int dj);
  /// After shift_window and update_bottom: cells that entered get w = max(-zeta, B) (rest: the
  /// surface under a pressure head sits zeta lower), every cell gets w >= B (no negative depth
  /// where the bottom rose).
  void rest_new_cells();

 private:
  std::size_t padded(int i, int j) const {
    return static_cast<std::size_t>(j + kGhost) * stride_ + static_cast<std::size_t>(i + kGhost);
  }
  std::size_t corner(int i, int j) const {
    return static_cast<std::size_t>(j + kGhost) * (stride_ + 1) + static_cast<std::size_t>(i + kGhost);
  }
  void fill_ghosts(std::vector<Real>& w, std::vector<Real>& hu, std::vector<Real>& hv) const;
  /// Where a forward-Euler stage writes: out = from + dt rate, or with `average` (Heun's second
  /// stage) out = (out + from + dt rate) / 2, then the round-off clamp of negative depths.
  struct EulerStage {
    double dt_s;
    bool average;
    std::vector<Real>*w, *hu, *hv;
  };
  /// One sweep over the rows of the state (w, hu, hv), ghosts filled: dU/dt row by row, and each
  /// row's Euler stage as soon as its rates are complete (euler), or (euler null) the rates into
  /// rate_. Returns the largest local speed (m/s) when euler is null (0 otherwise: nothing needs it).
  double sweep(const std::vector<Real>& w, const std::vector<Real>& hu, const std::vector<Real>& hv,
               const EulerStage* euler);
  /// The Euler stage of row j from its rates; returns the row's most negative depth before the
  /// clamp (0 when none).
  Real euler_row(const EulerStage& stage, int j, const std::vector<Real>& from_w, const std::vector<Real>& from_hu,
                 const std::vector<Real>& from_hv, const Real* rate_w, const Real* rate_hu, const Real* rate_hv);
  /// Ghosts of `from`, then one fused sweep: out = stage(from).
  void stage(std::vector<Real>& from_w, std::vector<Real>& from_hu, std::vector<Real>& from_hv, double dt_s,
             bool average, std::vector<Real>& w, std::vector<Real>& hu, std::vector<Real>& hv);

  static constexpr int kGhost = 2;
  int columns_, rows_;
  double spacing_m_;
  EdgeKind edges_;
  ShallowWaterOptions options_;
  std::size_t stride_;  // columns + 2 ghosts each side
  std::vector<Real> w_, hu_, hv_;
  std::vector<double> bottom_corner_, head_corner_;  // (stride + 1) x (rows + 2 ghosts + 1)
  std::vector<Real> b_east_, b_north_;  // B' = B + zeta at the east / north interface of each padded cell
  std::vector<Real> b_cell_, head_cell_;  // cell means of B and zeta
  std::vector<unsigned char> entered_;    // cells that entered in the last shift
  std::vector<Real> w1_, hu1_, hv1_;       // the first stage
  std::vector<Real> rate_[3];              // dU/dt of w, hu, hv (advance()'s first stage only)
  // Row buffers of one sweep (shallow_water.cpp sweep()): w' = w + zeta of the last kWpRows rows,
  // the rates of two rows, the x reconstruction of the row, the y reconstructions of this row and
  // the previous one, fluxes, local speeds and depths. A stage keeps a few rows in cache instead
  // of writing full-grid arrays: at 256 x 256 the grid's arrays no longer fit the core's L2.
  static constexpr int kWpRows = 4;
  std::vector<Real> wp_rows_, rate_rows_[3];
  struct RowFaces {
    std::vector<Real> w_high, w_low, normal_high, normal_low, tangential_high, tangential_low, source;
  };
  RowFaces x_faces_, y_faces_[2];
  std::vector<Real> flux_mass_, flux_normal_, flux_tangential_, speed_, depth_;
  double most_negative_depth_m_ = 0.0;
};

using ShallowWaterGrid = BasicShallowWaterGrid<double>;
using BowWaveGrid = BasicShallowWaterGrid<float>;
extern template class BasicShallowWaterGrid<double>;
extern template class BasicShallowWaterGrid<float>;

}  // namespace nearshore::ships
