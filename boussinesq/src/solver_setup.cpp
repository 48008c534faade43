// BoussinesqSolver's construction, in the steps its constructor runs: the grid and its cell fields
// taken and checked, the time step against the Courant limit, the scheme's parameters checked, the
// fingerprint of a saved state, the sweep frames (the time-independent coefficients of both
// orientations), the sponges, the state and work arrays, the fully nonlinear terms and the surface
// roller. The step is boussinesq_solver.cpp; docs/solver.md describes the scheme.
#include "nearshore/boussinesq/boussinesq_solver.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "solver_implementation.hpp"
#include "nearshore/core/error.hpp"

namespace nearshore::boussinesq {

using namespace nearshore::ocean;  // wave components, sea states, linear waves

namespace {

constexpr char kSubject[] = "Boussinesq solver";  // the object every set-up error names

std::size_t index(int c, int r, int cols) { return static_cast<std::size_t>(r) * cols + c; }

// The angular frequency of the wave maker's largest component, rad/s (0 for none): the peak wave of
// the dispersion taper's k h and of the roller's period.
double peak_angular_frequency_rad_s(const WaveMaker& wave_maker) {
  double peak_w = 0.0, peak_a = 0.0;
  for (const WaveComponent& c : wave_maker.sea_state.components)
    if (c.amplitude_m > peak_a) { peak_a = c.amplitude_m; peak_w = c.angular_frequency_rad_s; }
  return peak_w;
}

// The mean zero-up-crossing period of a record (about its mean, crossings interpolated linearly),
// or 0 with fewer than two crossings: the surface roller's period for a time-series wave maker.
double mean_zero_up_crossing_period_s(const std::vector<double>& time_s, const std::vector<double>& elevation_m) {
  double mean = 0.0;
  for (double v : elevation_m) mean += v / static_cast<double>(elevation_m.size());
  double first = -1.0, last = -1.0;
  int crossings = 0;
  for (std::size_t i = 1; i < elevation_m.size() && i < time_s.size(); ++i) {
    if (!(elevation_m[i - 1] < mean && elevation_m[i] >= mean)) continue;
    const double at = time_s[i - 1] + (time_s[i] - time_s[i - 1]) * (mean - elevation_m[i - 1]) / (elevation_m[i] - elevation_m[i - 1]);
    if (first < 0.0) first = at;
    last = at;
    ++crossings;
  }
  return crossings > 1 ? (last - first) / (crossings - 1) : 0.0;
}

double smooth_step(double t) {  // cubic 0..1 on t in [0, 1]
  t = std::clamp(t, 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

// The dispersion taper of docs/solver.md: 0 at or below the cut-off, 1 from twice the cut-off.
double dispersion_weight(double depth_m, const SolverParameters& p, double peak_angular_frequency_rad_s) {
  if (depth_m <= 0.0) return 0.0;
  double w = 1.0;
  if (p.dispersion_cutoff_depth_m > 0.0) w *= smooth_step(depth_m / p.dispersion_cutoff_depth_m - 1.0);
  if (p.dispersion_cutoff_kh > 0.0 && peak_angular_frequency_rad_s > 0.0) {
    const double kh = wavenumber_from_frequency(peak_angular_frequency_rad_s, depth_m) * depth_m;
    w *= smooth_step(kh / p.dispersion_cutoff_kh - 1.0);
  }
  return w;
}

// Each cell's distance in cells from the nearest land (d <= 0) or wall cell (porosity below
// kWallPorosity), counting a diagonal step as one (so a staircase's corner is as near as its faces),
// at most `cap`: two passes of a chamfer transform over the frame's layout (cell (c, l) at c * rows + l).
// The grid's edges are not land (the terms and the filter mirror there).
std::vector<int> land_distance_cells(const std::vector<float>& depth, const std::vector<float>& porosity, int cols, int rows, int cap) {
  std::vector<int> distance(depth.size(), cap);
  auto at = [&](int c, int l) -> int& { return distance[static_cast<std::size_t>(c) * rows + l]; };
  for (std::size_t i = 0; i < depth.size(); ++i)
    if (depth[i] <= 0.0f || porosity[i] < detail::kWallPorosity) distance[i] = 0;
  for (int c = 0; c < cols; ++c)
    for (int l = 0; l < rows; ++l) {
      int& d = at(c, l);
      if (l > 0) d = std::min(d, at(c, l - 1) + 1);
      if (c > 0)
        for (int k = std::max(l - 1, 0); k <= std::min(l + 1, rows - 1); ++k) d = std::min(d, at(c - 1, k) + 1);
    }
  for (int c = cols - 1; c >= 0; --c)
    for (int l = rows - 1; l >= 0; --l) {
      int& d = at(c, l);
      if (l + 1 < rows) d = std::min(d, at(c, l + 1) + 1);
      if (c + 1 < cols)
        for (int k = std::max(l - 1, 0); k <= std::min(l + 1, rows - 1); ++k) d = std::min(d, at(c + 1, k) + 1);
    }
  return distance;
}

// Builds the time-independent coefficients of one orientation from cell depth and porosity given
// in the frame's layout (cell (c along, l line) at c * rows + l; boussinesq_sweep.hpp). The face
// values the sweep derives from the cells (boussinesq_sweep.hpp) are used here for the taper and
// the porous blocks, so both agree by construction.
StaticFrame build_frame(std::vector<float> depth, std::vector<float> porosity, std::vector<float> stone_diameter_ratio, int cols, int rows,
                        double spacing_along_m, double spacing_across_m, const SolverParameters& p, double peak_w) {
  StaticFrame frame;
  frame.cols = cols;
  frame.rows = rows;
  frame.spacing_along_m = spacing_along_m;
  frame.spacing_across_m = spacing_across_m;
  frame.depth_m = std::move(depth);
  frame.porosity = std::move(porosity);
  frame.stone_diameter_ratio = std::move(stone_diameter_ratio);
  frame.inverse_porosity.resize(frame.depth_m.size());
  for (std::size_t i = 0; i < frame.porosity.size(); ++i)
    frame.inverse_porosity[i] =
        frame.porosity[i] >= detail::kWallPorosity ? static_cast<float>(1.0 / std::min(static_cast<double>(frame.porosity[i]), 1.0)) : 0.0f;
  // Porous resistance coefficients of seed 003 eq. (2) in the Van Gent (1995) form; the sweep
  // evaluates them from each face's porosity (a stone diameter of 0 means no porous resistance).
  // The laminar (Darcy) part takes the water's viscosity, the one of the laminar film's bed stress.
  if (p.porous.stone_diameter_m > 0.0) {
    frame.porous_laminar_factor = p.porous.laminar_alpha * p.kinematic_viscosity_m2_s;
    frame.porous_turbulent_factor = p.porous.turbulent_beta;
    frame.porous_stone_diameter_m = p.porous.stone_diameter_m;
  } else {
    frame.porous_stone_diameter_m = 1.0;  // factors 0: alpha = beta = 0 (and no division by 0)
  }
  const std::size_t faces = static_cast<std::size_t>(cols + 1) * rows;
  frame.face_dispersion_weight.assign(faces, 0.0f);
  // The taper beside land and walls (SolverParameters::taper_dispersion_at_walls): a face's weight
  // rises as smooth_step((n - 1) / p) with n the nearer of its two cells' distance from land in cells
  // (1 beside it), p the filter's half-order: 0 in the first row, full from p + 1 rows out.
  const int taper_cells = p.taper_dispersion_at_walls && p.shapiro_filter_order > 0 &&
                                  p.wall_dispersion == SolverParameters::WallDispersion::kEndBeforeWalls
                              ? p.shapiro_filter_order / 2
                              : 0;
  const std::vector<int> land_distance =
      taper_cells > 0 ? land_distance_cells(frame.depth_m, frame.porosity, cols, rows, taper_cells + 1) : std::vector<int>{};
  frame.block_is_porous.assign(static_cast<std::size_t>((rows + detail::kBlockLines - 1) / detail::kBlockLines), 0);
  for (int f = 1; f < cols; ++f)
    for (int l = 0; l < rows; ++l) {
      const std::size_t R = static_cast<std::size_t>(f) * rows + l, L = R - rows;
      const double wall_weight =
          taper_cells > 0 ? smooth_step((std::min(land_distance[L], land_distance[R]) - 1.0) / taper_cells) : 1.0;
      frame.face_dispersion_weight[R] =
          static_cast<float>(wall_weight * dispersion_weight(detail::face_depth(frame.depth_m.data(), L, R), p, peak_w));
      // Blocks of lines with a porous face run the sweep with the porous terms (boussinesq_sweep.cpp).
      if (detail::face_porosity(frame.porosity.data(), frame.inverse_porosity.data(), L, R) != 1.0)
        frame.block_is_porous[static_cast<std::size_t>(l / detail::kBlockLines)] = 1;
    }
  return frame;
}
}  // namespace

BoussinesqSolver::BoussinesqSolver(const HarbourGrid& harbour, const SolverParameters& parameters,
                                   const WaveMaker& wave_maker)
    : implementation_(std::make_unique<Implementation>()) {
  Implementation& s = *implementation_;
  s.take_grid(harbour, parameters);
  Implementation::CellFields cells = s.read_cell_fields(harbour);
  s.choose_time_step(cells.max_depth_m);
  s.check_scheme_parameters();
  const double peak_w = peak_angular_frequency_rad_s(wave_maker);
  // The order below keeps the peak memory at the steady state's: what is only needed while the
  // solver is built (transposed copies, the double depths of the fingerprint, sponge rates) is
  // released before the state and work arrays are allocated.
  s.take_fingerprint(cells.depth_m);
  s.set_sweep_constants();
  s.source = std::make_unique<detail::SourceFunction>(wave_maker, s.geometry, cells.depth_m, s.parameters);
  s.build_frames(std::move(cells), peak_w);
  s.build_sponges();
  s.allocate_state_and_work_arrays();
  s.set_up_current();
  s.set_up_fully_nonlinear_terms();
  s.eta_output = Raster<float>(s.nx, s.ny, 0.0f);
  s.breaking_output = Raster<float>(s.nx, s.ny, 0.0f);
  s.set_up_surface_roller(wave_maker, peak_w);
  s.publish();
}

void BoussinesqSolver::Implementation::take_grid(const HarbourGrid& harbour, const SolverParameters& solver_parameters) {
  const GridGeometry& grid = harbour.geometry;
  if (grid.columns < 3 || grid.rows < 1 || !(grid.spacing_x_m() > 0.0) || !(grid.spacing_y_m() > 0.0))
    throw Error(kSubject, "the harbour grid is " + std::to_string(grid.columns) + " x " + std::to_string(grid.rows) +
                              " cells of " + std::to_string(grid.spacing_x_m()) + " x " + std::to_string(grid.spacing_y_m()) + " m",
                "give at least 3 x 1 cells and positive spacings");
  if (harbour.still_water_depth_m.columns() != grid.columns || harbour.still_water_depth_m.rows() != grid.rows ||
      harbour.porosity.columns() != grid.columns || harbour.porosity.rows() != grid.rows)
    throw Error(kSubject, "the depth and porosity rasters do not match the grid geometry", "rebuild the harbour grid with nearshore bathy");
  geometry = grid;
  parameters = solver_parameters;
  nx = grid.columns;
  ny = grid.rows;
  dx = grid.spacing_x_m();
  dy = grid.spacing_y_m();
}

BoussinesqSolver::Implementation::CellFields BoussinesqSolver::Implementation::read_cell_fields(const HarbourGrid& harbour) const {
  if (!(parameters.effective_depth_limit_m >= 0.0))
    throw Error(kSubject, "SolverParameters::effective_depth_limit_m = " + std::to_string(parameters.effective_depth_limit_m) + " m",
                "give a positive depth, or 0 for no limit (docs/solver.md, \"Effective depth\")");
  const std::size_t cells = geometry.cell_count();
  // Depth and porosity stay in the harbour grid's float (exact); the solver computes in double.
  CellFields fields;
  std::vector<float>& depth = fields.depth_m;
  std::vector<float>& porosity = fields.porosity;
  depth.resize(cells);
  porosity.resize(cells);
  double max_depth = 0.0;
  for (std::size_t i = 0; i < cells; ++i) {
    // The effective-depth limit (docs/solver.md, "Effective depth"): the one depth every term, the
    // source function and the time step see; land (d <= 0) is never capped.
    depth[i] = harbour.still_water_depth_m.values()[i];
    if (parameters.effective_depth_limit_m > 0.0 && depth[i] > parameters.effective_depth_limit_m)
      depth[i] = static_cast<float>(parameters.effective_depth_limit_m);
    porosity[i] = std::clamp(harbour.porosity.values()[i], 0.0f, 1.0f);
    if (!std::isfinite(depth[i])) {
      const int c = static_cast<int>(i % nx), r = static_cast<int>(i / nx);
      throw Error(kSubject, "depth is not finite at cell (" + std::to_string(c) + ", " + std::to_string(r) + ")",
                  "fill the hole in the bathymetry (HarbourRequest::fill_uncovered_from_nearest when gridding it)");
    }
    max_depth = std::max(max_depth, static_cast<double>(depth[i]));
  }
  fields.max_depth_m = max_depth;
  fields.stone_diameter_ratio = read_stone_diameter_ratios(harbour);
  return fields;
}

std::vector<float> BoussinesqSolver::Implementation::read_stone_diameter_ratios(const HarbourGrid& harbour) const {
  // Each cell's stone diameter as a ratio to the solver's (StaticFrame::stone_diameter_ratio); none
  // for a grid without its own (every ratio 1, no array).
  std::vector<float> stone_ratio;
  if (harbour.porous_stone_diameter_m.size() == 0) return stone_ratio;
  const std::size_t cells = geometry.cell_count();
  stone_ratio.assign(cells, 1.0f);
  if (harbour.porous_stone_diameter_m.columns() != geometry.columns || harbour.porous_stone_diameter_m.rows() != geometry.rows)
    throw Error(kSubject, "the harbour grid's stone diameter raster does not match the grid geometry",
                "give HarbourGrid::porous_stone_diameter_m the grid's size, or leave it empty for the solver's stone diameter everywhere");
  const double solver_diameter = parameters.porous.stone_diameter_m > 0.0 ? parameters.porous.stone_diameter_m : 1.0;
  for (std::size_t i = 0; i < cells; ++i) {
    const float diameter = harbour.porous_stone_diameter_m.values()[i];
    if (!(diameter > 0.0f) || !std::isfinite(diameter)) {
      const int c = static_cast<int>(i % nx), r = static_cast<int>(i / nx);
      throw Error(kSubject, "HarbourGrid::porous_stone_diameter_m is " + std::to_string(diameter) + " m at cell (" + std::to_string(c) + ", " +
                                std::to_string(r) + ")",
                  "give every cell a positive stone diameter (the solver's, PorousResistance::stone_diameter_m, where it has none of its own)");
    }
    stone_ratio[i] = static_cast<float>(diameter / solver_diameter);
  }
  return stone_ratio;
}

void BoussinesqSolver::Implementation::choose_time_step(double max_depth) {
  // The time step and the Courant limit follow the smaller cell size: the gravity wave crosses a
  // cell of min(dx, dy) fastest (FUNWAVE-TVD and MIKE 21 BW likewise).
  const double smaller_spacing = std::min(dx, dy);
  if (max_depth <= 0.0) throw Error(kSubject, "the grid holds no water (every depth <= 0)", "check the sign of the depths (positive down)");
  // The gravity wave carried by the imposed current (courant_speed_m_s): sqrt(g d_max) without one.
  const double celerity = courant_speed_m_s(max_depth, parameters.current);
  dt = parameters.time_step_s > 0.0 ? parameters.time_step_s : parameters.courant_number * smaller_spacing / celerity;
  if (!(dt > 0.0)) throw Error(kSubject, "no time step: time_step_s and courant_number are both 0", "set one of them");
  const double courant = celerity * dt / smaller_spacing;
  if (courant > kMaxCourantNumber) {
    // The library-level guard: a bake case is checked against the same limit first, naming its key.
    const bool step_given = parameters.time_step_s > 0.0;
    std::ostringstream problem;
    if (step_given)
      problem << "SolverParameters::time_step_s = " << dt << " s gives";
    else
      problem << "SolverParameters::courant_number = " << parameters.courant_number << " (a time step of " << dt << " s) gives";
    if (parameters.current.any())
      problem << " a Courant number (|U| + sqrt(g d_max)) dt/min(dx, dy) = " << courant << " (|U| " << parameters.current.speed_m_s()
              << " m/s, SolverParameters::current; ";
    else
      problem << " a Courant number sqrt(g d_max) dt/min(dx, dy) = " << courant << " (";
    problem << "d_max " << max_depth << " m, the deepest cell; min(dx, dy) " << smaller_spacing << " m), above the stability limit "
            << kMaxCourantNumber;
    throw Error(kSubject, problem.str(),
                step_given ? "set SolverParameters::time_step_s to at most " + std::to_string(kMaxCourantNumber * smaller_spacing / celerity) +
                                 " s, or to 0 with SolverParameters::courant_number at most " + std::to_string(kMaxCourantNumber)
                           : "set SolverParameters::courant_number to at most " + std::to_string(kMaxCourantNumber));
  }
}

void BoussinesqSolver::Implementation::check_scheme_parameters() const {
  if (parameters.nonlinear_iterations < 1) throw Error(kSubject, "nonlinear_iterations must be at least 1", "set it to 2");
  if (parameters.shapiro_filter_order < 0 || parameters.shapiro_filter_order % 2 != 0 || parameters.shapiro_filter_order > 16)
    throw Error(kSubject, "shapiro_filter_order is " + std::to_string(parameters.shapiro_filter_order) + ", not an even order from 0 to 16",
                "set it to 8 (the default) or 0 to turn the filter off");
  if (parameters.adi_passes < 1) throw Error(kSubject, "adi_passes must be at least 1", "set it to 2 (the default; 1 is the faster, less accurate option)");
  if (parameters.equations == Equations::kFullyNonlinear && parameters.dispersion_depth == DispersionDepth::kTotal)
    throw Error(kSubject, "SolverParameters::equations = kFullyNonlinear with dispersion_depth = kTotal: the fully nonlinear terms already carry the total depth",
                "set dispersion_depth to kStillWater (the default) with the fully nonlinear equations");
  for (const SpongeLayer& sponge : parameters.sponges) {
    const double extent = (sponge.side == Side::kWest || sponge.side == Side::kEast) ? geometry.width_m() : geometry.height_m();
    if (!(sponge.width_m >= 0.0) || sponge.width_m > 0.5 * extent)
      throw Error(kSubject, "a sponge layer is " + std::to_string(sponge.width_m) + " m wide, the grid only " + std::to_string(extent) + " m",
                  "make each sponge at most half the grid");
  }
}

void BoussinesqSolver::Implementation::take_fingerprint(const std::vector<float>& depth) {
  // Fingerprint of everything a saved state must agree with (depth hashed as double, as written
  // since state version 1).
  const std::vector<double> depth_double(depth.begin(), depth.end());
  std::uint64_t h = hash_bytes(&nx, sizeof nx);
  h = hash_bytes(&ny, sizeof ny, h);
  h = hash_bytes(&dx, sizeof dx, h);
  if (dy != dx) h = hash_bytes(&dy, sizeof dy, h);  // square grids keep their fingerprint (saved states load)
  h = hash_bytes(&dt, sizeof dt, h);
  h = hash_bytes(depth_double.data(), depth_double.size() * sizeof(double), h);
  // The fully nonlinear equations carry a history in the state (nonlinear_dispersion.hpp); the
  // seed's equations keep their fingerprint, so their saved states load as before.
  if (parameters.equations == Equations::kFullyNonlinear) {
    const char tag[] = "fully nonlinear";
    h = hash_bytes(tag, sizeof tag, h);
  }
  // An imposed current changes the state's meaning (edges held, sponges towards it); none keeps
  // the fingerprint, so saved states without one load as before.
  if (parameters.current.any()) {
    const double velocity[2] = {parameters.current.velocity_x_m_s, parameters.current.velocity_y_m_s};
    h = hash_bytes(velocity, sizeof velocity, h);
  }
  fingerprint = h;
}

void BoussinesqSolver::Implementation::set_sweep_constants() {
  constants = {dt, parameters.dispersion_coefficient, parameters.dry_depth_m, parameters.chezy_coefficient,
               parameters.kinematic_viscosity_m2_s,
               parameters.nonlinear_iterations,
               parameters.dispersion_depth == DispersionDepth::kTotal,
               parameters.face_depth == SolverParameters::FaceDepth::kMeanWhereWet,
               parameters.equations == Equations::kFullyNonlinear,
               parameters.wall_dispersion == SolverParameters::WallDispersion::kMirrorAtWalls,
               parameters.current.any(),
               parameters.current.any() ? 0.0 : 1.0};
}

void BoussinesqSolver::Implementation::build_frames(CellFields cells, double peak_w) {
  // frame_x from transposed copies, released before frame_y takes the natural-layout fields.
  {
    const std::size_t count = cells.depth_m.size();
    std::vector<float> depth_t(count), porosity_t(count), stone_ratio_t(cells.stone_diameter_ratio.size());
    detail::transpose(cells.depth_m.data(), depth_t.data(), nx, ny);
    detail::transpose(cells.porosity.data(), porosity_t.data(), nx, ny);
    if (!cells.stone_diameter_ratio.empty()) detail::transpose(cells.stone_diameter_ratio.data(), stone_ratio_t.data(), nx, ny);
    frame_x = build_frame(std::move(depth_t), std::move(porosity_t), std::move(stone_ratio_t), nx, ny, dx, dy, parameters, peak_w);
  }
  frame_y = build_frame(std::move(cells.depth_m), std::move(cells.porosity), std::move(cells.stone_diameter_ratio), ny, nx, dy, dx, parameters,
                        peak_w);
}

void BoussinesqSolver::Implementation::build_sponges() {
  // Sponges (Larsen & Dancy 1983 in spirit): damping rate sigma = sigma_max r^2, r = 0 at the inner
  // edge and 1 at the boundary, sigma_max = 8 sqrt(g d) / width so a wave crossing the layer
  // and back loses e^{-5} of its amplitude; applied as a factor 1 / (1 + sigma dt) per step, kept
  // only where it is not 1 (the factor 1 leaves a value as it is).
  if (parameters.sponges.empty()) return;
  const float* const cell_depth = frame_y.depth_m.data();
  const std::size_t cells = geometry.cell_count();
  std::vector<double> sigma(cells, 0.0);
  for (int r = 0; r < ny; ++r)
    for (int c = 0; c < nx; ++c) {
      double rate = 0.0;
      const double d = std::max(static_cast<double>(cell_depth[index(c, r, nx)]), parameters.dry_depth_m);
      for (const SpongeLayer& sponge : parameters.sponges) {
        if (sponge.width_m <= 0.0) continue;
        double distance = 0.0;
        switch (sponge.side) {
          case Side::kWest: distance = (c + 0.5) * dx; break;
          case Side::kEast: distance = (nx - c - 0.5) * dx; break;
          case Side::kSouth: distance = (r + 0.5) * dy; break;
          case Side::kNorth: distance = (ny - r - 0.5) * dy; break;
        }
        if (distance < sponge.width_m) {
          const double x = 1.0 - distance / sponge.width_m;
          rate = std::max(rate, 8.0 * std::sqrt(kGravity_m_s2 * d) / sponge.width_m * x * x);
        }
      }
      sigma[index(c, r, nx)] = rate;
    }
  for (int f = 1; f < nx; ++f)
    for (int r = 0; r < ny; ++r) {
      const double sum = sigma[index(f - 1, r, nx)] + sigma[index(f, r, nx)];
      if (sum != 0.0) sponge_faces_x.push_back({px(f, r), 1.0 / (1.0 + dt * 0.5 * sum)});
    }
  std::sort(sponge_faces_x.begin(), sponge_faces_x.end(),
            [](const auto& a, const auto& b) { return a.index < b.index; });
  for (int k = 1; k < ny; ++k)
    for (int c = 0; c < nx; ++c) {
      const double sum = sigma[index(c, k - 1, nx)] + sigma[index(c, k, nx)];
      if (sum != 0.0) sponge_faces_y.push_back({qy(c, k), 1.0 / (1.0 + dt * 0.5 * sum)});
    }
  for (std::size_t i = 0; i < cells; ++i)
    if (sigma[i] != 0.0) sponge_cells.push_back({i, 1.0 / (1.0 + dt * sigma[i])});
  for (auto* points : {&sponge_cells, &sponge_faces_x, &sponge_faces_y}) points->shrink_to_fit();
}

double BoussinesqSolver::Implementation::current_flux_x_m2_s(int f, int r) const {
  // P = u d on a face between two open water cells; the grid's edge faces take their one cell.
  const float* depth = frame_x.depth_m.data();
  const float* inverse_porosity = frame_x.inverse_porosity.data();
  const std::size_t L = px(std::max(f - 1, 0), r), R = px(std::min(f, nx - 1), r);
  if (!(depth[L] > 0.0f && depth[R] > 0.0f && inverse_porosity[L] > 0.0f && inverse_porosity[R] > 0.0f)) return 0.0;
  return parameters.current.velocity_x_m_s * detail::face_depth(depth, L, R);
}

double BoussinesqSolver::Implementation::current_flux_y_m2_s(int c, int k) const {
  const float* depth = frame_y.depth_m.data();
  const float* inverse_porosity = frame_y.inverse_porosity.data();
  const std::size_t S = index(c, std::max(k - 1, 0), nx), N = index(c, std::min(k, ny - 1), nx);
  if (!(depth[S] > 0.0f && depth[N] > 0.0f && inverse_porosity[S] > 0.0f && inverse_porosity[N] > 0.0f)) return 0.0;
  return parameters.current.velocity_y_m_s * detail::face_depth(depth, S, N);
}

void BoussinesqSolver::Implementation::set_current_fluxes() {
  for (int f = 0; f <= nx; ++f)
    for (int r = 0; r < ny; ++r) flux_x[px(f, r)] = current_flux_x_m2_s(f, r);
  for (int k = 0; k <= ny; ++k)
    for (int c = 0; c < nx; ++c) flux_y[qy(c, k)] = current_flux_y_m2_s(c, k);
  // The edges hold their flux for good, so what flows in must flow out, or the level drifts for as
  // long as the bake runs: u d over a west edge deeper than the east one brings in more than it
  // takes out. The outgoing edge fluxes are scaled by inflow / outflow (1 over a flat bed, exactly).
  double inflow_m3_s = 0.0, outflow_m3_s = 0.0;
  auto tally = [&](double flux_m2_s, double inward_sign, double length_m) {
    (flux_m2_s * inward_sign > 0.0 ? inflow_m3_s : outflow_m3_s) += std::abs(flux_m2_s) * length_m;
  };
  for (int r = 0; r < ny; ++r) {
    tally(flux_x[px(0, r)], 1.0, dy);
    tally(flux_x[px(nx, r)], -1.0, dy);
  }
  for (int c = 0; c < nx; ++c) {
    tally(flux_y[qy(c, 0)], 1.0, dx);
    tally(flux_y[qy(c, ny)], -1.0, dx);
  }
  if (!(inflow_m3_s > 0.0 && outflow_m3_s > 0.0))
    throw Error(kSubject,
                "the imposed current (" + std::to_string(parameters.current.velocity_x_m_s) + ", " +
                    std::to_string(parameters.current.velocity_y_m_s) + ") m/s has " +
                    (inflow_m3_s > 0.0 ? "no water edge to leave the grid by" : "no water edge to enter the grid by"),
                "give the current a direction that crosses open water at two edges of the grid");
  const double scale = inflow_m3_s / outflow_m3_s;
  if (scale == 1.0) return;
  auto scale_outgoing = [&](double& flux_m2_s, double inward_sign) {
    if (flux_m2_s * inward_sign < 0.0) flux_m2_s *= scale;
  };
  for (int r = 0; r < ny; ++r) {
    scale_outgoing(flux_x[px(0, r)], 1.0);
    scale_outgoing(flux_x[px(nx, r)], -1.0);
  }
  for (int c = 0; c < nx; ++c) {
    scale_outgoing(flux_y[qy(c, 0)], 1.0);
    scale_outgoing(flux_y[qy(c, ny)], -1.0);
  }
}

void BoussinesqSolver::Implementation::set_up_current() {
  // The imposed current (SolverParameters::current, docs/solver.md "Currents"): the flux it starts
  // from, and the flux the sponges relax towards, at each of their faces.
  if (!parameters.current.any()) return;
  set_current_fluxes();
  sponge_target_x.resize(sponge_faces_x.size());
  for (std::size_t k = 0; k < sponge_faces_x.size(); ++k) sponge_target_x[k] = flux_x[sponge_faces_x[k].index];
  sponge_target_y.resize(sponge_faces_y.size());
  for (std::size_t k = 0; k < sponge_faces_y.size(); ++k) sponge_target_y[k] = flux_y[sponge_faces_y[k].index];
}

void BoussinesqSolver::Implementation::allocate_state_and_work_arrays() {
  const float* const cell_depth = frame_y.depth_m.data();
  const std::size_t cells = geometry.cell_count();
  const std::size_t faces_x = static_cast<std::size_t>(nx + 1) * ny, faces_y = static_cast<std::size_t>(nx) * (ny + 1);
  eta.assign(cells, 0.0);
  for (std::size_t i = 0; i < cells; ++i)
    if (cell_depth[i] < 0.0f) eta[i] = -static_cast<double>(cell_depth[i]);  // dry land: the surface is the ground (h = 0)
  flux_x.assign(faces_x, 0.0);
  flux_y.assign(faces_y, 0.0);
  eta_previous_t.assign(cells, 0.0);
  detail::transpose(eta.data(), eta_previous_t.data(), nx, ny);
  flux_x_increment.assign(faces_x, 0.0);
  flux_y_increment.assign(faces_y, 0.0);
  eddy_viscosity.assign(cells, 0.0f);
  eddy_t.assign(cells, 0.0f);
  breaking_start_s.assign(cells, -1.0);
  for (auto* v : {&eta_t, &eta_star, &eta_next, &eta_base}) v->assign(cells, 0.0);
  flux_x_new.assign(faces_x, 0.0);
  flux_y_new.assign(faces_y, 0.0);
  for (auto* v : {&tangential_half, &tangential_rate}) v->assign(std::max(faces_x, faces_y), 0.0);
  if (parameters.adi_passes > 1) {
    flux_guess.assign(std::max(faces_x, faces_y), 0.0);
    eta_pass_t.assign(cells, 0.0);
  }
  flux_filter = detail::ShapiroFilter(parameters.shapiro_filter_order / 2);
  filterable_x.assign(faces_x, 0);
  filterable_y.assign(faces_y, 0);
  dispersive.assign(cells, 0);
  dispersive_t.assign(cells, 0);
  wet_cells.assign(cells, 0);
}

void BoussinesqSolver::Implementation::set_up_fully_nonlinear_terms() {
  if (parameters.equations != Equations::kFullyNonlinear) return;
  nonlinear = std::make_unique<detail::NonlinearDispersion>(detail::NonlinearDispersionGrid{
      nx, ny, dx, dy, frame_y.depth_m.data(), frame_y.porosity.data(), frame_x.face_dispersion_weight.data(),
      frame_y.face_dispersion_weight.data(), parameters.dispersion_coefficient, parameters.dry_depth_m,
      parameters.wall_dispersion == SolverParameters::WallDispersion::kMirrorAtWalls, parameters.current.any()});
  breaking_strength_t.assign(geometry.cell_count(), 0.0f);
  fade_nonlinear = parameters.breaking.enabled && parameters.breaking.model == BreakingParameters::Model::kEddyViscosity &&
                   parameters.breaking.fade_fully_nonlinear_terms;
}

void BoussinesqSolver::Implementation::set_up_surface_roller(const WaveMaker& wave_maker, double peak_w) {
  if (!(parameters.breaking.enabled && parameters.breaking.model == BreakingParameters::Model::kRoller)) return;
  // The half time of the roller's front angle (Madsen et al. 1997: t_1/2 = T/5) from the wave
  // maker's period: the peak component's, or the mean zero-up-crossing period of a time series.
  const BreakingParameters& b = parameters.breaking;
  double period_s = peak_w > 0.0 ? 2.0 * std::numbers::pi / peak_w : 0.0;
  if (period_s == 0.0 && wave_maker.kind == WaveMaker::Kind::kTimeSeries)
    period_s = mean_zero_up_crossing_period_s(wave_maker.series_time_s, wave_maker.series_elevation_m);
  const double half_time_s = b.roller_half_time_s > 0.0 ? b.roller_half_time_s : b.roller_half_time_periods * period_s;
  if (!(half_time_s > 0.0))
    throw Error(kSubject, "the surface roller (BreakingParameters::model = kRoller) needs the half time of its front angle, and the wave maker has no period to take it from",
                "set BreakingParameters::roller_half_time_s (Madsen et al. 1997: a fifth of the wave period)");
  if (!(b.roller_final_angle_deg > 0.0) || b.roller_final_angle_deg > b.roller_onset_angle_deg || !(b.roller_onset_angle_deg < 90.0))
    throw Error(kSubject, "the roller's angles are phi_B = " + std::to_string(b.roller_onset_angle_deg) + " and phi_0 = " +
                              std::to_string(b.roller_final_angle_deg) + " degrees",
                "give 0 < roller_final_angle_deg <= roller_onset_angle_deg < 90 (Madsen et al. 1997: 10 and 20)");
  const double degree = std::numbers::pi / 180.0;
  detail::RollerConstants roller_constants{std::tan(b.roller_onset_angle_deg * degree), std::tan(b.roller_final_angle_deg * degree),
                                           half_time_s, b.roller_onset_angle_deg * degree, b.roller_final_angle_deg * degree,
                                           b.roller_celerity_factor, b.roller_shape_factor, parameters.dry_depth_m};
  roller = std::make_unique<detail::SurfaceRoller>(
      detail::RollerGrid{nx, ny, dx, dy, frame_y.depth_m.data(), frame_y.porosity.data()}, roller_constants);
  if (b.roller_filter_order < 0 || b.roller_filter_order % 2 != 0 || b.roller_filter_order > 16)
    throw Error(kSubject, "roller_filter_order is " + std::to_string(b.roller_filter_order) + ", not an even order from 0 to 16",
                "give BreakingParameters::roller_filter_order = 4 (the default) or 0 for no surf-zone filter");
  if (b.roller_filter_order > 0) {
    const std::size_t cells = geometry.cell_count();
    surf_zone_filter = detail::ShapiroFilter(b.roller_filter_order / 2);
    surf_zone_cells.assign(cells, 0);
    surf_zone_scratch.assign(cells, 0);
    surf_zone_x.assign(static_cast<std::size_t>(nx + 1) * ny, 0);
    surf_zone_y.assign(static_cast<std::size_t>(nx) * (ny + 1), 0);
  }
}

}  // namespace nearshore::boussinesq
