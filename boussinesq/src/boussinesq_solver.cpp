// BoussinesqSolver: the time step (ADI: an x sweep on transposed data and a y sweep, in alternating
// order if asked), the moving shoreline's positivity repair, the grid-scale flux filter, sponges,
// Kennedy et al. (2000) breaking (the surface roller option: surface_roller.cpp). The construction is
// solver_setup.cpp, the state I/O boussinesq_state.cpp, initial conditions initial_conditions.cpp.
// docs/solver.md describes the scheme; boussinesq_sweep.cpp holds the discretised equations.
#include "nearshore/boussinesq/boussinesq_solver.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <atomic>
#include <cstring>
#include <istream>
#include <limits>
#include <ostream>
#include <sstream>
#include <vector>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "solver_implementation.hpp"
#include "nearshore/core/error.hpp"

namespace nearshore::boussinesq {

using namespace nearshore::ocean;  // wave components, sea states, linear waves

namespace {


std::size_t index(int c, int r, int cols) { return static_cast<std::size_t>(r) * cols + c; }

// A cell holds water: open (porosity > 0) and its water depth d + eta above the wet/dry threshold.
// `&`, not `&&`, so the loops that call it vectorise.
inline bool holds_water(float inverse_porosity, float still_water_depth_m, double eta_m, double dry_depth_m) {
  return (inverse_porosity > 0.0f) & (still_water_depth_m + eta_m > dry_depth_m);
}

// body(i) for i in [0, count), in parallel chunks: element-wise work, so the result does not
// depend on the thread count.
template <class Body>
void for_each_index(std::size_t count, const Body& body) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 16384), [&](const tbb::blocked_range<std::size_t>& range) {
    for (std::size_t i = range.begin(); i < range.end(); ++i) body(i);
  });
}

// Scans of the whole grid go in blocks of 1024: a block is checked without a branch (the loop
// vectorises), in parallel over blocks, and only a block holding a hit element by element. These
// scans run every step (the stability guard, the shoreline repair): serial, they were 4 % of a
// step's samples on one thread and all of the second thread's idle time (perf, issue 15).
constexpr std::size_t kScanBlock = 1024;

template <class Hit>
int block_has_hit(std::size_t block, std::size_t count, const Hit& hit) {
  const std::size_t begin = block * kScanBlock, end = std::min(count, begin + kScanBlock);
  int any = 0;
  for (std::size_t i = begin; i < end; ++i) any |= hit(i);
  return any;
}

// The first i in [0, count) with bad(i) != 0 (an int 0 or 1), or count. The lowest block with a
// hit wins whatever the thread count (an atomic minimum), so the answer is the serial one.
template <class Bad>
std::size_t first_index_where(std::size_t count, const Bad& bad) {
  const std::size_t blocks = (count + kScanBlock - 1) / kScanBlock;
  std::atomic<std::size_t> first_block{blocks};
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, blocks, 16), [&](const tbb::blocked_range<std::size_t>& range) {
    for (std::size_t b = range.begin(); b < range.end(); ++b) {
      if (b >= first_block.load(std::memory_order_relaxed)) return;
      if (block_has_hit(b, count, bad) == 0) continue;
      std::size_t seen = first_block.load(std::memory_order_relaxed);
      while (b < seen && !first_block.compare_exchange_weak(seen, b, std::memory_order_relaxed)) {
      }
      return;
    }
  });
  const std::size_t block = first_block.load();
  for (std::size_t i = block * kScanBlock; i < std::min(count, (block + 1) * kScanBlock); ++i)
    if (bad(i) != 0) return i;
  return count;
}

// Every i in [0, count) with hit(i) != 0, in increasing order (blocks flagged in parallel, then
// gathered in order: the same list for any thread count).
template <class Hit>
void append_indices_where(std::size_t count, const Hit& hit, std::vector<std::size_t>& out) {
  const std::size_t blocks = (count + kScanBlock - 1) / kScanBlock;
  std::vector<unsigned char> flagged(blocks);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, blocks, 16), [&](const tbb::blocked_range<std::size_t>& range) {
    for (std::size_t b = range.begin(); b < range.end(); ++b) flagged[b] = static_cast<unsigned char>(block_has_hit(b, count, hit));
  });
  for (std::size_t b = 0; b < blocks; ++b)
    if (flagged[b] != 0)
      for (std::size_t i = b * kScanBlock; i < std::min(count, (b + 1) * kScanBlock); ++i)
        if (hit(i) != 0) out.push_back(i);
}

}  // namespace

BoussinesqSolver::~BoussinesqSolver() = default;

void BoussinesqSolver::Implementation::mark_dispersive(const StaticFrame& frame, const double* eta_frame, unsigned char* mask) {
  // The dispersive terms apply where the cell and its 4 neighbours are wet (docs/solver.md); beyond
  // the grid edges the neighbour is the edge cell itself (the mirror of a wall). With
  // WallDispersion::kMirrorAtWalls a dry neighbour behind a wall counts as that mirror too
  // (detail::kMirror*, boussinesq_sweep.hpp): a cell of porosity 0, or a bed higher than this
  // cell's by a cell's length or more (a step steeper than 1:1: a quay, a pier, a breakwater's
  // face). So the water beside a wall has the dispersive terms as the water beside the grid's edges
  // has them, with the wall's cell read as the mirror of this one, per direction (docs/solver.md,
  // "Walls and the dispersive terms"). A beach's dry cell (a gentler step) is no wall: the mask
  // ends one cell before the shoreline. Two passes: wet cells, then the 5-point product.
  const int cols = frame.cols, rows = frame.rows;
  const double dry = parameters.dry_depth_m;
  const float along_m = static_cast<float>(frame.spacing_along_m), across_m = static_cast<float>(frame.spacing_across_m);
  const float* depth = frame.depth_m.data();
  const float* inverse_porosity = frame.inverse_porosity.data();
  unsigned char* wet = wet_cells.data();
  tbb::parallel_for(0, cols, [&](int c) {
    const std::size_t line = static_cast<std::size_t>(c) * rows;
    for (int l = 0; l < rows; ++l)
      wet[line + l] = holds_water(inverse_porosity[line + l], depth[line + l], eta_frame[line + l], dry);
  });
  if (parameters.wall_dispersion == SolverParameters::WallDispersion::kEndBeforeWalls) {
    // The cell and its 4 neighbours wet: a product over contiguous lanes, which vectorises.
    tbb::parallel_for(0, cols, [&](int c) {
      const unsigned char* here = wet + static_cast<std::size_t>(c) * rows;
      const unsigned char* before = wet + static_cast<std::size_t>(std::max(c - 1, 0)) * rows;
      const unsigned char* after = wet + static_cast<std::size_t>(std::min(c + 1, cols - 1)) * rows;
      unsigned char* out = mask + static_cast<std::size_t>(c) * rows;
      for (int l = 1; l + 1 < rows; ++l) out[l] = here[l] & before[l] & after[l] & here[l - 1] & here[l + 1];
      out[0] = here[0] & before[0] & after[0] & here[std::min(1, rows - 1)];
      if (rows > 1) out[rows - 1] = here[rows - 1] & before[rows - 1] & after[rows - 1] & here[rows - 2];
    });
    return;
  }
  // kMirrorAtWalls: a neighbour is a mirrored wall when it is dry and of porosity 0 or its bed at
  // least a cell's length above this cell's (not a shoreline). Beyond the grid's edges the neighbour
  // is the cell itself, which is never a wall of a wet cell. Byte arithmetic over the lines, no
  // branch (whether GCC vectorises it was not checked: with the option this loop was 4 % of the demo
  // harbour's bake, the default's 5-point product 2 %).
  tbb::parallel_for(0, cols, [&](int c) {
    const std::size_t line = static_cast<std::size_t>(c) * rows;
    const std::size_t line_before = static_cast<std::size_t>(std::max(c - 1, 0)) * rows;
    const std::size_t line_after = static_cast<std::size_t>(std::min(c + 1, cols - 1)) * rows;
    const unsigned char *here = wet + line, *before = wet + line_before, *after = wet + line_after;
    const float *depth_here = depth + line, *depth_before = depth + line_before, *depth_after = depth + line_after;
    const float *open_here = inverse_porosity + line, *open_before = inverse_porosity + line_before,
                *open_after = inverse_porosity + line_after;
    unsigned char* out = mask + line;
    auto cell = [&](int l, int south, int north) __attribute__((always_inline)) {
      const float d = depth_here[l];
      // A neighbour is a wall: dry, and closed (porosity 0) or a step up of at least `step_m`.
      auto wall = [d](unsigned char wet_neighbour, float open_neighbour, float depth_neighbour, float step_m) {
        return static_cast<unsigned char>((1 - wet_neighbour) & ((open_neighbour == 0.0f) | (d - depth_neighbour >= step_m)));
      };
      const unsigned char wall_before = wall(before[l], open_before[l], depth_before[l], along_m);
      const unsigned char wall_after = wall(after[l], open_after[l], depth_after[l], along_m);
      const unsigned char wall_south = wall(here[south], open_here[south], depth_here[south], across_m);
      const unsigned char wall_north = wall(here[north], open_here[north], depth_here[north], across_m);
      const unsigned char dispersive = here[l] & (before[l] | wall_before) & (after[l] | wall_after) & (here[south] | wall_south) &
                                       (here[north] | wall_north);
      out[l] = static_cast<unsigned char>(dispersive * (detail::kDispersive + detail::kMirrorBefore * wall_before + detail::kMirrorAfter * wall_after +
                                                        detail::kMirrorSouth * wall_south + detail::kMirrorNorth * wall_north));
    };
    for (int l = 1; l + 1 < rows; ++l) cell(l, l - 1, l + 1);
    cell(0, 0, std::min(1, rows - 1));
    if (rows > 1) cell(rows - 1, rows - 2, rows - 1);
  });
}

void BoussinesqSolver::Implementation::step() {
  // dt/dx, and dx/dy for the y divergence: ratio (dP + aspect dQ) = dt (dP/dx + dQ/dy), and square
  // cells (aspect exactly 1) keep the square scheme's bits.
  const double ratio = dt / dx, aspect = dx / dy;

  // One ADI step is a pair of sweeps, x then y on even steps and y then x on odd steps when
  // `alternate_sweep_order` is set (docs/solver.md, "Sweep order"). The FIRST sweep of a pair has
  //   E = eta^n - dt/n (dP^n/dx + dQ^n/dy) + dt S   (seed 003 eq. 1, the flux across the lines explicit)
  // and estimates everything ACROSS its lines at t^{n+1/2}: on pass 0 from the last steps (the other
  // flux at t^n + its last increment / 2, its rate lagged half a step as its last increment / dt,
  // eta extrapolated from eta^{n-1} and eta^n); on later passes (`adi_passes` > 1) from the previous
  // pass. The SECOND sweep has E = eta* (the first sweep's result) and the other flux at t^{n+1/2}
  // and its rate exactly. Layouts: the x sweep works on transposed arrays (suffix _t), the y sweep
  // on the natural row-major ones (boussinesq_sweep.hpp).
  const bool x_first = !parameters.alternate_sweep_order || step_count % 2 == 0;
  // The surface roller of the state at t^n (breaking model kRoller): its force acts on this step.
  // eta^{n-1} in the natural layout goes to eta_next (free until the sweeps write it).
  if (roller) {
    detail::transpose(eta_previous_t.data(), eta_next.data(), ny, nx);
    roller_active = roller->update(time_s, eta.data(), eta_next.data(), flux_x.data(), flux_y.data(), breaking_start_s.data(),
                                   breaking_output.values().data());
  }
  detail::transpose(eta.data(), eta_t.data(), nx, ny);
  if (eddy_viscosity_active) detail::transpose(eddy_viscosity.data(), eddy_t.data(), nx, ny);
  if (eddy_viscosity_active && fade_nonlinear) detail::transpose(breaking_output.values().data(), breaking_strength_t.data(), nx, ny);
  // B by which the fully nonlinear terms fade, per layout: zeros (breaking_strength_t) when they do not.
  const float* fade_x = nonlinear ? breaking_strength_t.data() : nullptr;
  const float* fade_natural = nonlinear ? (fade_nonlinear ? breaking_output.values().data() : breaking_strength_t.data()) : nullptr;
  mark_dispersive(frame_x, eta_t.data(), dispersive_t.data());
  mark_dispersive(frame_y, eta.data(), dispersive.data());
  // The fully nonlinear terms' subcritical factors of this step, from the state at t^n and the masks
  // of this step (eta_next and eta_base as scratch: the sweeps write both before reading them).
  if (nonlinear)
    nonlinear->update_subcritical(eta.data(), flux_x.data(), flux_y.data(), dispersive.data(), eta_next.data(), eta_base.data());

  // The normal flux's first guess: last step's increment on pass 0 (the state array itself), this
  // step's previous pass afterwards. The sweep takes the flux at t^{n+1/2} as old + guess / 2.
  auto normal_guess = [&](int pass, const std::vector<double>& old_flux, const std::vector<double>& last_increment,
                          const std::vector<double>& new_flux) -> const double* {
    if (pass == 0) return last_increment.data();
    for_each_index(old_flux.size(), [&](std::size_t f) { flux_guess[f] = new_flux[f] - old_flux[f]; });
    return flux_guess.data();
  };
  // E of the first sweep: eta^n minus the divergence of the fluxes at t^n, plus the wave maker.
  auto explicit_base = [&](const double* eta_layout, double* base, bool x_layout) {
    tbb::parallel_for(0, ny, [&](int r) {
      for (int c = 0; c < nx; ++c) {
        const std::size_t i = x_layout ? px(c, r) : index(c, r, nx);
        const double divergence =
            flux_x[px(c + 1, r)] - flux_x[px(c, r)] + flux_y[qy(c, r + 1)] * aspect - flux_y[qy(c, r)] * aspect;
        base[i] = eta_layout[i] - ratio * frame_y.inverse_porosity[index(c, r, nx)] * divergence;
      }
    });
    if (x_layout)
      source->add(time_s + 0.5 * dt, dt, base, static_cast<std::size_t>(ny), 1);
    else
      source->add(time_s + 0.5 * dt, dt, base, 1, static_cast<std::size_t>(nx));
  };
  // The other flux at t^{n+1/2} and its rate, in the sweep's tangential layout (transposed: the
  // x-face P into the y sweep's layout, the y-face Q into the x sweep's). Exact when the other sweep
  // has run this pass (from its new flux); otherwise estimated from its change over the last step
  // (pass 0) or over this step's previous pass.
  enum class Across { kEstimate, kExact };
  auto tangential_from = [&](Across kind, int pass, const std::vector<double>& old_flux, const std::vector<double>& new_flux,
                             const std::vector<double>& last_increment, int cols, int rows) {
    double *half = tangential_half.data(), *rate = tangential_rate.data();
    if (kind == Across::kExact)
      detail::transpose_half_and_rate(detail::HalfAndRate::kFromNewFlux, old_flux.data(), new_flux.data(), dt, half, rate,
                                      cols, rows);
    else if (pass == 0)
      detail::transpose_half_and_rate(detail::HalfAndRate::kFromIncrement, old_flux.data(), last_increment.data(), dt, half,
                                      rate, cols, rows);
    else
      detail::transpose_half_and_rate(detail::HalfAndRate::kFromPass, old_flux.data(), new_flux.data(), dt, half, rate, cols,
                                      rows);
  };
  // eta at t^{n+1/2} for the derivatives across a sweep's lines is computed in the sweep from eta^n
  // and a partner (SweepInput): eta^{n-1} (extrapolated, first sweep of pass 0), the previous pass's
  // eta^{n+1} (first sweep of later passes) or this pass's eta* (second sweep: the mean).

  auto sweep_x = [&](bool first, int pass) {
    tangential_from(first ? Across::kEstimate : Across::kExact, pass, flux_y, flux_y_new, flux_y_increment, nx, ny + 1);
    const double* partner = eta_base.data();
    bool extrapolates = false;
    if (first) {
      if (pass == 0) {
        // E depends on the state at t^n alone: the same on every pass. With x first no sweep between
        // two passes writes eta_base (the y sweep's E is eta*), so later passes keep the first's.
        explicit_base(eta_t.data(), eta_base.data(), true);
        partner = eta_previous_t.data();
        extrapolates = true;
      } else {  // the previous pass's eta^{n+1}, transposed
        detail::transpose(eta_next.data(), eta_pass_t.data(), nx, ny);
        partner = eta_pass_t.data();
      }
    } else {
      // After the y sweep: E = eta*, Q at t^{n+1/2} and dQ/dt exact.
      detail::transpose(eta_star.data(), eta_base.data(), nx, ny);
    }
    sweep(frame_x,
          {eta_t.data(), eta_base.data(), partner, extrapolates, flux_x.data(),
           normal_guess(pass, flux_x, flux_x_increment, flux_x_new), tangential_half.data(), tangential_rate.data(),
           eddy_t.data(), dispersive_t.data(), eddy_viscosity_active, nonlinear ? nonlinear->force_x() : nullptr,
           nonlinear ? nonlinear->subcritical_x() : nullptr, fade_x},
          // Its eta (eta* when it comes first, eta^{n+1} when second) straight into the natural layout.
          {first ? eta_star.data() : eta_next.data(), flux_x_new.data(), 1, static_cast<std::size_t>(nx)});
  };

  auto sweep_y = [&](bool first, int pass) {
    tangential_from(first ? Across::kEstimate : Across::kExact, pass, flux_x, flux_x_new, flux_x_increment, ny, nx + 1);
    const double* base = eta_star.data();
    const double* partner = eta_star.data();
    bool extrapolates = false;
    if (first) {
      explicit_base(eta.data(), eta_base.data(), false);
      base = eta_base.data();
      partner = eta_next.data();  // pass > 0: the previous pass's eta^{n+1}
      if (pass == 0) {  // eta^{n-1} in the natural layout, in eta_next (free until the x sweep writes it)
        detail::transpose(eta_previous_t.data(), eta_next.data(), ny, nx);
        extrapolates = true;
      }
    }
    sweep(frame_y,
          {eta.data(), base, partner, extrapolates, flux_y.data(), normal_guess(pass, flux_y, flux_y_increment, flux_y_new),
           tangential_half.data(), tangential_rate.data(), eddy_viscosity.data(), dispersive.data(), eddy_viscosity_active,
           nonlinear ? nonlinear->force_y() : nullptr, nonlinear ? nonlinear->subcritical_y() : nullptr, fade_natural},
          {first ? eta_star.data() : eta_next.data(), flux_y_new.data(), static_cast<std::size_t>(nx), 1});
  };

  for (int pass = 0; pass < parameters.adi_passes; ++pass) {
    if (x_first) {
      sweep_x(true, pass);
      sweep_y(false, pass);
    } else {
      sweep_y(true, pass);
      sweep_x(false, pass);
    }
  }

  // The roller's momentum flux, explicit (docs/solver.md, "Breaking: the surface roller").
  if (roller_active) add_roller_force();

  // 3. Moving shoreline: no cell may end with negative depth (mass-conserving flux limiting).
  repair_negative_depths();

  // 4. Shapiro filter of the fluxes against the fine-grid two-dimensional mode (docs/solver.md).
  filter_grid_scale_fluxes();

  // 5. Advance the state.
  for_each_index(flux_x.size(), [&](std::size_t f) {
    flux_x_increment[f] = flux_x_new[f] - flux_x[f];
    flux_x[f] = flux_x_new[f];
  });
  for_each_index(flux_y.size(), [&](std::size_t f) {
    flux_y_increment[f] = flux_y_new[f] - flux_y[f];
    flux_y[f] = flux_y_new[f];
  });
  eta_previous_t.swap(eta_t);  // eta^n, transposed
  eta_star.swap(eta);          // eta_star now holds eta^n (natural), for the breaking model
  eta.swap(eta_next);          // eta = eta^{n+1}
  // The fully nonlinear remainder of this step, centred at t^{n+1/2}, for the next (before the
  // sponges, which damp the state after the step). Its scratch: work arrays free until the next
  // step (eta_next holds eta*, eta_base and eta_t spent values, the tangential arrays the last
  // sweep's, flux_x_new a copy of flux_x).
  if (nonlinear) {
    double* const scratch[6] = {eta_next.data(), eta_base.data(), eta_t.data(), tangential_half.data(), tangential_rate.data(),
                                flux_x_new.data()};
    nonlinear->update({eta_star.data(), eta.data(), flux_x.data(), flux_x_increment.data(), flux_y.data(),
                       flux_y_increment.data(), dispersive.data(), dt, fade_nonlinear ? fade_natural : nullptr},
                      scratch);
  }
  apply_sponges();
  update_breaking(eta_star);
  time_s += dt;
  ++step_count;
  publish();
}

void BoussinesqSolver::Implementation::repair_negative_depths() {
  // The step's mass fluxes are F = (P^n + P^{n+1})/2 (and likewise for Q). Where a cell would
  // end below its bed, its outgoing fluxes are scaled down so it ends exactly dry; the neighbours
  // that lose that inflow are revisited. Serial over the few shoreline cells, in a fixed order,
  // so the result does not depend on the thread count. Mass is conserved exactly.
  const float* depth = frame_y.depth_m.data();
  std::vector<std::size_t> pending;
  const std::size_t cells = static_cast<std::size_t>(nx) * ny;
  const float* inverse_porosity = frame_y.inverse_porosity.data();
  const double* level = eta_next.data();
  append_indices_where(cells, [&](std::size_t i) {
    return static_cast<int>(inverse_porosity[i] > 0.0f) & static_cast<int>(depth[i] + level[i] < 0.0);
  }, pending);
  const double ratio_x = dt / dx, ratio_y = dt / dy;  // a face's flux over the step in metres of level
  for (int pass = 0; pass < 20 && !pending.empty(); ++pass) {
    std::vector<std::size_t> next;
    for (std::size_t i : pending) {
      const double h = depth[i] + eta_next[i];
      if (h >= 0.0) continue;
      const int c = static_cast<int>(i % nx), r = static_cast<int>(i / nx);
      // Faces: west, east (x), south, north (y); outgoing sign for each.
      struct FaceRef { double* new_flux; const double* old_flux; double outward; std::ptrdiff_t neighbour; double ratio; };
      const std::size_t fw = px(c, r), fe = px(c + 1, r), fs = qy(c, r), fn = qy(c, r + 1);
      FaceRef faces[4] = {
          {&flux_x_new[fw], &flux_x[fw], -1.0, c > 0 ? static_cast<std::ptrdiff_t>(i) - 1 : -1, ratio_x},
          {&flux_x_new[fe], &flux_x[fe], 1.0, c + 1 < nx ? static_cast<std::ptrdiff_t>(i) + 1 : -1, ratio_x},
          {&flux_y_new[fs], &flux_y[fs], -1.0, r > 0 ? static_cast<std::ptrdiff_t>(i) - nx : -1, ratio_y},
          {&flux_y_new[fn], &flux_y[fn], 1.0, r + 1 < ny ? static_cast<std::ptrdiff_t>(i) + nx : -1, ratio_y}};
      double outflow = 0.0;  // metres of water level over the step (times n)
      for (const FaceRef& face : faces) {
        const double mass_flux = 0.5 * (*face.new_flux + *face.old_flux) * face.outward;
        if (mass_flux > 0.0) outflow += mass_flux * face.ratio;
      }
      if (outflow <= 0.0) { eta_next[i] = -depth[i]; continue; }  // round-off only
      const double n = 1.0 / frame_y.inverse_porosity[i];
      const double keep = std::clamp(1.0 + n * h / outflow, 0.0, 1.0);  // fraction of the outflow kept
      for (FaceRef& face : faces) {
        const double mass_flux = 0.5 * (*face.new_flux + *face.old_flux) * face.outward;
        if (mass_flux <= 0.0) continue;
        const double removed = (1.0 - keep) * mass_flux;  // outward mass flux taken away
        *face.new_flux -= 2.0 * removed * face.outward;
        if (face.neighbour >= 0) {
          const std::size_t j = static_cast<std::size_t>(face.neighbour);
          eta_next[j] -= removed * face.ratio * frame_y.inverse_porosity[j];
          if (depth[j] + eta_next[j] < 0.0) next.push_back(j);
        }
      }
      eta_next[i] += (1.0 - keep) * outflow * frame_y.inverse_porosity[i];
    }
    std::sort(next.begin(), next.end());
    next.erase(std::unique(next.begin(), next.end()), next.end());
    pending.swap(next);
  }
}

void BoussinesqSolver::Implementation::filter_grid_scale_fluxes() {
  const bool surf_zone = roller_active && surf_zone_filter.half_order() > 0;
  if (flux_filter.half_order() <= 0 && !surf_zone) return;
  // A face may be filtered where it is open (or a grid-edge wall, which the odd ghosts describe)
  // and the cells on both sides are wet with every neighbour wet: never across a shoreline or quay.
  const unsigned char* wet_x = dispersive_t.data();  // eta^n masks of this step (mark_dispersive)
  const unsigned char* wet_y = dispersive.data();
  // The edge faces of an imposed current hold its flux: not filtered, and so no face whose stencil
  // reaches them (the filter's ghosts beyond a wall are odd, a flux through it would be pulled to 0).
  const unsigned char edge = parameters.current.any() ? 0 : 1;
  tbb::parallel_for(0, nx + 1, [&](int f) {
    unsigned char* out = filterable_x.data() + px(f, 0);
    if (f == 0 || f == nx) {
      std::fill(out, out + ny, edge);
      return;
    }
    const float* inverse_porosity = frame_x.inverse_porosity.data();
    const unsigned char *west = wet_x + px(f - 1, 0), *east = wet_x + px(f, 0);
    for (int r = 0; r < ny; ++r)
      out[r] = (detail::face_open(inverse_porosity, px(f - 1, r), px(f, r)) != 0.0) & (west[r] == detail::kDispersive) & (east[r] == detail::kDispersive);  // & not &&: vectorises
  });
  tbb::parallel_for(0, ny + 1, [&](int k) {
    unsigned char* out = filterable_y.data() + qy(0, k);
    if (k == 0 || k == ny) {
      std::fill(out, out + nx, edge);
      return;
    }
    const float* inverse_porosity = frame_y.inverse_porosity.data();
    const unsigned char *south = wet_y + index(0, k - 1, nx), *north = wet_y + index(0, k, nx);
    for (int c = 0; c < nx; ++c)
      out[c] = (detail::face_open(inverse_porosity, index(c, k - 1, nx), index(c, k, nx)) != 0.0) & (south[c] == detail::kDispersive) & (north[c] == detail::kDispersive);
  });
  if (flux_filter.half_order() > 0) {
    // P: along x is its slow index (normal to the west and east walls), along y its fast index.
    flux_filter.along_slow(flux_x_new.data(), filterable_x.data(), nx + 1, ny, true);
    flux_filter.along_fast(flux_x_new.data(), filterable_x.data(), nx + 1, ny, false);
    // Q: along y is its slow index (normal to the south and north walls), along x its fast index.
    flux_filter.along_slow(flux_y_new.data(), filterable_y.data(), ny + 1, nx, true);
    flux_filter.along_fast(flux_y_new.data(), filterable_y.data(), ny + 1, nx, false);
  }
  if (surf_zone) filter_surf_zone_fluxes();
}

void BoussinesqSolver::Implementation::filter_surf_zone_fluxes() {
  // The surf zone: cells with a roller force on one of their faces (the roller and the cell its
  // 1-2-1 smoothing reaches), dilated by three cells along each axis so that the filter's 5-point
  // stencil (order 4) covers the roller and the short waves just behind its front.
  constexpr int kReach = 3;
  const std::vector<double>& force_x = roller->force_x();
  const std::vector<double>& force_y = roller->force_y();
  unsigned char* zone = surf_zone_cells.data();
  unsigned char* scratch = surf_zone_scratch.data();
  tbb::parallel_for(0, ny, [&](int r) {
    for (int c = 0; c < nx; ++c)
      scratch[index(c, r, nx)] = (force_x[px(c, r)] != 0.0) | (force_x[px(c + 1, r)] != 0.0) | (force_y[qy(c, r)] != 0.0) |
                                 (force_y[qy(c, r + 1)] != 0.0);
  });
  tbb::parallel_for(0, ny, [&](int r) {  // dilate along x
    for (int c = 0; c < nx; ++c) {
      unsigned char near = 0;
      for (int k = std::max(0, c - kReach); k <= std::min(nx - 1, c + kReach); ++k) near |= scratch[index(k, r, nx)];
      zone[index(c, r, nx)] = near;
    }
  });
  tbb::parallel_for(0, ny, [&](int r) {  // then along y
    for (int c = 0; c < nx; ++c) {
      unsigned char near = 0;
      for (int k = std::max(0, r - kReach); k <= std::min(ny - 1, r + kReach); ++k) near |= zone[index(c, k, nx)];
      scratch[index(c, r, nx)] = near;
    }
  });
  // A face is in the surf zone when a cell beside it is, and filterable as for the grid-wide filter.
  tbb::parallel_for(0, nx + 1, [&](int f) {
    for (int r = 0; r < ny; ++r) {
      const unsigned char near = (f > 0 ? scratch[index(f - 1, r, nx)] : 0) | (f < nx ? scratch[index(f, r, nx)] : 0);
      surf_zone_x[px(f, r)] = filterable_x[px(f, r)] & near;
    }
  });
  tbb::parallel_for(0, ny + 1, [&](int k) {
    for (int c = 0; c < nx; ++c) {
      const unsigned char near = (k > 0 ? scratch[index(c, k - 1, nx)] : 0) | (k < ny ? scratch[index(c, k, nx)] : 0);
      surf_zone_y[qy(c, k)] = filterable_y[qy(c, k)] & near;
    }
  });
  surf_zone_filter.along_slow(flux_x_new.data(), surf_zone_x.data(), nx + 1, ny, true);
  surf_zone_filter.along_fast(flux_x_new.data(), surf_zone_x.data(), nx + 1, ny, false);
  surf_zone_filter.along_slow(flux_y_new.data(), surf_zone_y.data(), ny + 1, nx, true);
  surf_zone_filter.along_fast(flux_y_new.data(), surf_zone_y.data(), ny + 1, nx, false);
}

void BoussinesqSolver::Implementation::apply_sponges() {
  const float* depth = frame_y.depth_m.data();
  const double dry = parameters.dry_depth_m;
  auto damp = [](const std::vector<SpongePoint>& points, const auto& body) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, points.size(), 4096), [&](const tbb::blocked_range<std::size_t>& range) {
      for (std::size_t k = range.begin(); k < range.end(); ++k) body(points[k]);
    });
  };
  // Towards the still-water level: a tide's (set_still_water_level), else the grid's 0, where
  // level + (eta - level) f is eta f to the bit (x - 0 and 0 + x are exact; a -0 becomes +0).
  const double level = still_water_level_m;
  damp(sponge_cells, [&](const SpongePoint& point) {
    const std::size_t i = point.index;
    if (depth[i] > 0.0f && depth[i] + eta[i] > dry) eta[i] = level + (eta[i] - level) * point.factor;
  });
  if (parameters.current.any()) {
    // Towards the imposed current's flux, not rest (docs/solver.md, "Currents"): the waves are
    // absorbed, the current passes through.
    auto relax = [&](const std::vector<SpongePoint>& points, const std::vector<double>& target, std::vector<double>& flux) {
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, points.size(), 4096), [&](const tbb::blocked_range<std::size_t>& range) {
        for (std::size_t k = range.begin(); k < range.end(); ++k) {
          double& value = flux[points[k].index];
          value = target[k] + (value - target[k]) * points[k].factor;
        }
      });
    };
    relax(sponge_faces_x, sponge_target_x, flux_x);
    relax(sponge_faces_y, sponge_target_y, flux_y);
    return;
  }
  damp(sponge_faces_x, [&](const SpongePoint& point) { flux_x[point.index] *= point.factor; });
  damp(sponge_faces_y, [&](const SpongePoint& point) { flux_y[point.index] *= point.factor; });
}

void BoussinesqSolver::Implementation::add_roller_force() {
  // P^{n+1} += dt F(t^n): the roller's force from the state at t^n, added to the fluxes the sweeps
  // solved (a split step, first order in time like the closure's own time scale T/5 >> dt). The
  // mass equation sees it from the next step on; volume stays conserved (interior faces only).
  const std::vector<double>& force_x = roller->force_x();
  const std::vector<double>& force_y = roller->force_y();
  for_each_index(flux_x_new.size(), [&](std::size_t f) { flux_x_new[f] += dt * force_x[f]; });
  for_each_index(flux_y_new.size(), [&](std::size_t f) { flux_y_new[f] += dt * force_y[f]; });
}

void BoussinesqSolver::Implementation::update_breaking(const std::vector<double>& eta_old) {
  const BreakingParameters& b = parameters.breaking;
  // nu never changes without breaking or with the roller (updated at the start of step()): eddy_t,
  // transposed this step, stays right.
  if (!b.enabled || roller) {
    eddy_viscosity_active = false;
    return;
  }
  // Kennedy et al. (2000): a cell breaks while eta_t > eta_t*, the threshold falling linearly from
  // onset * sqrt(g d) at the start of the event to stop * sqrt(g d) after T* = factor sqrt(d/g);
  // strength B = clamp(eta_t / eta_t* - 1, 0, 1); eddy viscosity nu = B delta^2 (d + eta) eta_t
  // (eq. 6-7). The thresholds and T* are on the still-water depth d, the viscosity on the total
  // depth, as the paper writes them (sqrt(g h) and (h + eta) with h the still-water depth; FUNWAVE-TVD's
  // documentation likewise). On the total depth the threshold rose with the crest it was judging:
  // Hansen & Svendsen's spilling waves broke 0.3 m late (docs/validation.md).
  // (The sweeps cap nu at 0.2 dx^2/dt in the explicit cross terms of eq. (6)-(7) only.)
  // The event belongs to the wave front, not to the cell (Kennedy et al.'s "age of the breaking
  // event"; FUNWAVE-TVD's breaker carries it from cell to cell likewise): a cell the front reaches
  // with eta_t above the final threshold joins the event of its upwind neighbour (the side the
  // front comes from, -grad eta pointing the way it travels) and takes its start time, so the age
  // travels with the front. Without it every cell of the inner surf zone needed the onset
  // steepness anew, and a bore that had fallen below it crossed the surf zone without dissipation
  // (Hansen & Svendsen's surf zones kept 1.5-2 times the measured height; docs/solver.md).
  const float* depth = frame_y.depth_m.data();
  float* breaking_strength = breaking_output.values().data();
  const double g = kGravity_m_s2, delta2 = b.mixing_length_coefficient * b.mixing_length_coefficient;
  const double now = time_s + dt;
  std::atomic<bool> any_viscosity{false};
  // The start times before this update (every cell reads its neighbours' as they were): eta_base is
  // free at the end of a step.
  double* const started = eta_base.data();
  std::copy(breaking_start_s.begin(), breaking_start_s.end(), started);
  auto joined_event = [&](std::size_t i) {
    const int c = static_cast<int>(i % nx), r = static_cast<int>(i / nx);
    const double slope_x = eta[index(std::min(c + 1, nx - 1), r, nx)] - eta[index(std::max(c - 1, 0), r, nx)];
    const double slope_y = eta[index(c, std::min(r + 1, ny - 1), nx)] - eta[index(c, std::max(r - 1, 0), nx)];
    double joined = -1.0;
    auto consider = [&](int cc, int rr) {
      if (cc < 0 || cc >= nx || rr < 0 || rr >= ny) return;
      const double start = started[index(cc, rr, nx)];
      if (start >= 0.0 && (joined < 0.0 || start < joined)) joined = start;  // the older event
    };
    // Upwind: the front travels along -grad eta, so it comes from the +grad eta side.
    if (slope_x != 0.0) consider(slope_x > 0.0 ? c + 1 : c - 1, r);
    if (slope_y != 0.0) consider(c, slope_y > 0.0 ? r + 1 : r - 1);
    return joined;
  };
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, eta.size(), 4096), [&](const tbb::blocked_range<std::size_t>& range) {
    bool block_viscosity = false;
    for (std::size_t i = range.begin(); i < range.end(); ++i) {
      const double h = depth[i] + eta[i];
      if (depth[i] <= 0.0f || h <= parameters.dry_depth_m || frame_y.inverse_porosity[i] == 0.0) {
        eddy_viscosity[i] = 0.0f; breaking_strength[i] = 0.0f; breaking_start_s[i] = -1.0;
        continue;
      }
      const double still_depth = std::max(static_cast<double>(depth[i]), parameters.dry_depth_m);
      const double eta_t = (eta[i] - eta_old[i]) / dt, celerity = std::sqrt(g * still_depth);
      if (breaking_start_s[i] < 0.0 && eta_t > b.onset_celerity_fraction * celerity) breaking_start_s[i] = now;
      if (breaking_start_s[i] < 0.0 && eta_t > b.stop_celerity_fraction * celerity) breaking_start_s[i] = joined_event(i);
      double strength = 0.0;
      if (breaking_start_s[i] >= 0.0) {
        const double transition = b.transition_time_factor * std::sqrt(still_depth / g);
        const double age = std::clamp((now - breaking_start_s[i]) / transition, 0.0, 1.0);
        const double threshold = celerity * (b.onset_celerity_fraction + age * (b.stop_celerity_fraction - b.onset_celerity_fraction));
        strength = std::clamp(eta_t / threshold - 1.0, 0.0, 1.0);
        if (eta_t <= threshold) breaking_start_s[i] = -1.0;  // the event is over
      }
      breaking_strength[i] = static_cast<float>(strength);  // an output, 0..1: nothing reads it back
      eddy_viscosity[i] = static_cast<detail::EddyViscosity>(strength * delta2 * h * std::max(eta_t, 0.0));
      block_viscosity = block_viscosity || eddy_viscosity[i] != 0.0;
    }
    if (block_viscosity) any_viscosity.store(true, std::memory_order_relaxed);
  });
  // When the last breaking cell stops, eddy_t is cleared once; afterwards the transpose is skipped.
  if (eddy_viscosity_active && !any_viscosity.load()) {
    std::fill(eddy_t.begin(), eddy_t.end(), detail::EddyViscosity{0});
    std::fill(breaking_strength_t.begin(), breaking_strength_t.end(), 0.0f);  // B is 0 wherever nu is
  }
  eddy_viscosity_active = any_viscosity.load();
}

void BoussinesqSolver::Implementation::publish() {
  for_each_index(eta.size(), [&](std::size_t i) {
    eta_output.values()[i] = static_cast<float>(eta[i]);
  });
}

void BoussinesqSolver::set_surface_elevation(const std::function<double(double, double)>& surface_elevation_m) {
  Implementation& s = *implementation_;
  for (int r = 0; r < s.ny; ++r)
    for (int c = 0; c < s.nx; ++c) {
      const std::size_t i = index(c, r, s.nx);
      if (s.frame_y.depth_m[i] > 0.0 && s.frame_y.inverse_porosity[i] > 0.0)
        s.eta[i] = surface_elevation_m(s.geometry.cell_centre_x_m(c), s.geometry.cell_centre_y_m(r));
    }
  detail::transpose(s.eta.data(), s.eta_previous_t.data(), s.nx, s.ny);
  for (auto* v : {&s.flux_x, &s.flux_y, &s.flux_x_increment, &s.flux_y_increment}) std::fill(v->begin(), v->end(), 0.0);
  if (s.parameters.current.any()) s.set_current_fluxes();  // "rest" is the imposed current
  if (s.nonlinear) s.nonlinear->reset();
  s.publish();
}

void BoussinesqSolver::set_initial_condition(const std::function<double(double, double)>& surface_elevation_m,
                                             const std::function<double(double, double)>& flux_x_m2_s,
                                             const std::function<double(double, double)>& flux_y_m2_s) {
  Implementation& s = *implementation_;
  const GridGeometry& g = s.geometry;
  for (int r = 0; r < s.ny; ++r)
    for (int c = 0; c < s.nx; ++c) {
      const std::size_t i = index(c, r, s.nx);
      if (s.frame_y.depth_m[i] > 0.0) s.eta[i] = surface_elevation_m(g.cell_centre_x_m(c), g.cell_centre_y_m(r));
    }
  for (int f = 1; f < s.nx; ++f)
    for (int r = 0; r < s.ny; ++r)
      if (detail::face_open(s.frame_x.inverse_porosity.data(), s.px(f - 1, r), s.px(f, r)) != 0.0 &&
          detail::face_depth(s.frame_x.depth_m.data(), s.px(f - 1, r), s.px(f, r)) > 0.0)
        s.flux_x[s.px(f, r)] = flux_x_m2_s(g.origin_x_m + f * s.dx, g.cell_centre_y_m(r));
  for (int k = 1; k < s.ny; ++k)
    for (int c = 0; c < s.nx; ++c)
      if (detail::face_open(s.frame_y.inverse_porosity.data(), index(c, k - 1, s.nx), index(c, k, s.nx)) != 0.0 &&
          detail::face_depth(s.frame_y.depth_m.data(), index(c, k - 1, s.nx), index(c, k, s.nx)) > 0.0)
        s.flux_y[s.qy(c, k)] = flux_y_m2_s(g.cell_centre_x_m(c), g.origin_y_m + k * s.dy);
  detail::transpose(s.eta.data(), s.eta_previous_t.data(), s.nx, s.ny);
  for (auto* v : {&s.flux_x_increment, &s.flux_y_increment}) std::fill(v->begin(), v->end(), 0.0);
  if (s.nonlinear) s.nonlinear->reset();
  s.publish();
}

void BoussinesqSolver::set_still_water_level(double level_m, LevelChange change) {
  Implementation& s = *implementation_;
  if (!std::isfinite(level_m))
    throw Error("Boussinesq solver", "the still-water level is " + std::to_string(level_m) + " m", "give a finite level in metres");
  const double change_m = level_m - s.still_water_level_m;
  s.still_water_level_m = level_m;
  if (change == LevelChange::kStateHoldsIt || change_m == 0.0) return;
  // Every cell holding water now (above the dry depth, not a wall) rises or falls by the change, and
  // eta^{n-1} with it, so that the extrapolation to t^{n+1/2} sees no jump; a falling level leaves a
  // cell no lower than its bed. A dry beach cell is wetted by the flux from its risen neighbour.
  const float* depth = s.frame_y.depth_m.data();
  const float* inverse_porosity = s.frame_y.inverse_porosity.data();
  const double dry = s.parameters.dry_depth_m;
  for (int r = 0; r < s.ny; ++r)
    for (int c = 0; c < s.nx; ++c) {
      const std::size_t i = index(c, r, s.nx), t = s.px(c, r);
      const double d = depth[i];
      if (!(inverse_porosity[i] > 0.0f) || !(d + s.eta[i] > dry)) continue;
      const double moved = std::max(s.eta[i] + change_m, -d) - s.eta[i];
      s.eta[i] += moved;
      s.eta_previous_t[t] += moved;
    }
  s.publish();
}

double BoussinesqSolver::still_water_level_m() const { return implementation_->still_water_level_m; }

void BoussinesqSolver::step() { implementation_->step(); }
double BoussinesqSolver::time_s() const { return implementation_->time_s; }
double BoussinesqSolver::time_step_s() const { return implementation_->dt; }
long BoussinesqSolver::step_count() const { return implementation_->step_count; }
const GridGeometry& BoussinesqSolver::geometry() const { return implementation_->geometry; }
const Raster<float>& BoussinesqSolver::surface_elevation_m() const { return implementation_->eta_output; }
const Raster<float>& BoussinesqSolver::breaking_indicator() const { return implementation_->breaking_output; }

void BoussinesqSolver::cell_centred_fluxes(Raster<float>& flux_x_m2_s, Raster<float>& flux_y_m2_s) const {
  const Implementation& s = *implementation_;
  if (flux_x_m2_s.columns() != s.nx || flux_x_m2_s.rows() != s.ny) flux_x_m2_s = Raster<float>(s.nx, s.ny);
  if (flux_y_m2_s.columns() != s.nx || flux_y_m2_s.rows() != s.ny) flux_y_m2_s = Raster<float>(s.nx, s.ny);
  for (int r = 0; r < s.ny; ++r)
    for (int c = 0; c < s.nx; ++c) {
      flux_x_m2_s(c, r) = static_cast<float>(0.5 * (s.flux_x[s.px(c, r)] + s.flux_x[s.px(c + 1, r)]));
      flux_y_m2_s(c, r) = static_cast<float>(0.5 * (s.flux_y[index(c, r, s.nx)] + s.flux_y[index(c, r + 1, s.nx)]));
    }
}

namespace {

// The value of `value_at(cell index)` at a point: bilinear between the four cell centres around it,
// over those that hold water now (wet, porosity > 0; their weights renormalised). A dry cell's eta
// is its ground (h = 0) and a wall's is 0, and neither is the water a gauge beside a quay or in the
// swash should read (its mean level would take the ground's height with the cell's weight); where
// none of the four is wet the gauge reads the nearest cell: the ground it stands on.
template <class Implementation, class ValueAt>
auto wet_bilinear_at(const Implementation& s, double x_m, double y_m, const ValueAt& value_at) {
  const double u = std::clamp((x_m - s.geometry.origin_x_m) / s.dx - 0.5, 0.0, s.nx - 1.0);
  const double v = std::clamp((y_m - s.geometry.origin_y_m) / s.dy - 0.5, 0.0, s.ny - 1.0);
  const int c0 = std::min(static_cast<int>(u), s.nx - 1), r0 = std::min(static_cast<int>(v), s.ny - 1);
  const int c1 = std::min(c0 + 1, s.nx - 1), r1 = std::min(r0 + 1, s.ny - 1);
  const double a = u - c0, b = v - r0;
  const int columns[4] = {c0, c1, c0, c1}, rows[4] = {r0, r0, r1, r1};
  const double weights[4] = {(1 - a) * (1 - b), a * (1 - b), (1 - a) * b, a * b};
  decltype(value_at(std::size_t{0}, 0, 0)) weighted{};
  double wet_weight = 0.0;
  for (int k = 0; k < 4; ++k) {
    const std::size_t i = index(columns[k], rows[k], s.nx);
    if (holds_water(s.frame_y.inverse_porosity[i], s.frame_y.depth_m[i], s.eta[i], s.parameters.dry_depth_m)) {
      const auto value = value_at(i, columns[k], rows[k]);
      for (std::size_t n = 0; n < value.size(); ++n) weighted[n] += weights[k] * value[n];
      wet_weight += weights[k];
    }
  }
  if (wet_weight > 0.0) {
    for (auto& component : weighted) component /= wet_weight;
    return weighted;
  }
  const int c = a < 0.5 ? c0 : c1, r = b < 0.5 ? r0 : r1;
  return value_at(index(c, r, s.nx), c, r);
}

}  // namespace

double BoussinesqSolver::surface_elevation_at(double x_m, double y_m) const {
  const Implementation& s = *implementation_;
  return wet_bilinear_at(s, x_m, y_m, [&](std::size_t i, int, int) { return std::array<double, 1>{s.eta[i]}; })[0];
}

std::array<double, 2> BoussinesqSolver::flux_at(double x_m, double y_m) const {
  const Implementation& s = *implementation_;
  return wet_bilinear_at(s, x_m, y_m, [&](std::size_t, int c, int r) {
    return std::array<double, 2>{0.5 * (s.flux_x[s.px(c, r)] + s.flux_x[s.px(c + 1, r)]),
                                 0.5 * (s.flux_y[index(c, r, s.nx)] + s.flux_y[index(c, r + 1, s.nx)])};
  });
}

std::optional<InstabilityReport> BoussinesqSolver::check_stability() const {
  const Implementation& s = *implementation_;
  const double ratio = s.parameters.blowup_elevation_depth_ratio;
  // The bake calls this every step: a branch-free scan for the first bad cell (in row order, so the
  // report is the same as a cell-by-cell search), the report built only for it. A value is bad when
  // it is not finite (|v| <= max fails for NaN and infinities) or exceeds the guard.
  constexpr double kLargest = std::numeric_limits<double>::max();
  const std::size_t cells = s.eta.size();
  const std::size_t first_bad = first_index_where(cells, [&](std::size_t i) {
    const double d = s.frame_y.depth_m[i], eta = s.eta[i];
    const double excess = d > 0.0 ? std::abs(eta) : d + eta;
    return static_cast<int>(!(std::abs(eta) <= kLargest)) | static_cast<int>(excess > ratio * std::max(d, 1.0));
  });
  for (int r = static_cast<int>(first_bad / s.nx); r < s.ny; ++r)
    for (int c = r == static_cast<int>(first_bad / s.nx) ? static_cast<int>(first_bad % s.nx) : 0; c < s.nx; ++c) {
      const std::size_t i = index(c, r, s.nx);
      const double d = s.frame_y.depth_m[i], eta = s.eta[i];
      InstabilityReport report{s.time_s, c, r, s.geometry.cell_centre_x_m(c), s.geometry.cell_centre_y_m(r), d, eta, {}};
      if (!std::isfinite(eta)) {
        report.what = "surface elevation is not a number";
        return report;
      }
      const double excess = d > 0.0 ? std::abs(eta) : d + eta;  // on land: the water depth
      if (excess > ratio * std::max(d, 1.0)) {
        std::ostringstream what;
        what << "surface elevation " << eta << " m exceeds " << ratio << " x max(depth, 1 m)";
        report.what = what.str();
        return report;
      }
    }
  auto all_finite = [&](const std::vector<double>& values) {
    return first_index_where(values.size(), [&](std::size_t i) { return static_cast<int>(!(std::abs(values[i]) <= kLargest)); }) ==
           values.size();
  };
  if (all_finite(s.flux_x) && all_finite(s.flux_y)) return std::nullopt;
  for (std::size_t f = 0; f < s.flux_x.size(); ++f)
    if (!std::isfinite(s.flux_x[f])) {
      const int r = static_cast<int>(f % s.ny), c = std::min(static_cast<int>(f / s.ny), s.nx - 1);
      return InstabilityReport{s.time_s, c, r, s.geometry.cell_centre_x_m(c), s.geometry.cell_centre_y_m(r),
                               s.frame_y.depth_m[index(c, r, s.nx)], s.flux_x[f], "flux P is not a number"};
    }
  for (std::size_t f = 0; f < s.flux_y.size(); ++f)
    if (!std::isfinite(s.flux_y[f])) {
      const int r = std::min(static_cast<int>(f / s.nx), s.ny - 1), c = static_cast<int>(f % s.nx);
      return InstabilityReport{s.time_s, c, r, s.geometry.cell_centre_x_m(c), s.geometry.cell_centre_y_m(r),
                               s.frame_y.depth_m[index(c, r, s.nx)], s.flux_y[f], "flux Q is not a number"};
    }
  return std::nullopt;
}

double streamed_bytes_per_cell_step(const SolverParameters& parameters, bool breaking) {
  // Bytes per cell of each pass of step(), reads + 2 x writes (docs/solver.md "Memory traffic").
  constexpr double kDouble = 8, kFloat = 4, kMask = 1, kWrite = 2;
  // A sweep: eta^n, E, the eta partner, the normal flux and its guess, the tangential flux at
  // t^{n+1/2} and its rate (doubles); depth, porosity, 1/n, the taper (floats); the mask; writes eta and the flux.
  const double sweep = 7 * kDouble + 4 * kFloat + kMask + (breaking ? kFloat : 0.0) + kWrite * 2 * kDouble;
  const double transpose = kDouble + kWrite * kDouble;
  const double masks = 2 * (kDouble + 2 * kFloat + kWrite * kMask + 3 * kMask + kWrite * kMask);  // mark_dispersive, 2 layouts
  const double explicit_base = 3 * kDouble + kFloat + kWrite * kDouble;
  const double tangential = 2 * kDouble + kWrite * 2 * kDouble;  // transpose_half_and_rate
  const double extra_transposes = parameters.alternate_sweep_order ? 1.5 : 1.0;  // E of the second x sweep; eta^{n-1} when y is first
  const double pair = 2 * sweep + explicit_base + 2 * tangential + extra_transposes * transpose;
  const double repair_scan = kDouble + 2 * kFloat;
  const double filter = parameters.shapiro_filter_order > 0
                            ? 2 * (kFloat + 2 * kMask + kWrite * kMask) + 2 * 2 * (kDouble + kMask + kWrite * kDouble)
                            : 0.0;
  const double advance = 2 * (2 * kDouble + kWrite * 2 * kDouble);  // increments and fluxes
  const double breaking_pass = parameters.breaking.enabled ? 2 * kDouble + 3 * kFloat + kDouble + kWrite * (2 * kFloat + kDouble) : 0.0;
  const double publish = kDouble + kWrite * kFloat;
  const double eddy_transpose = breaking ? kFloat + kWrite * kFloat : 0.0;
  return transpose + masks + parameters.adi_passes * pair + repair_scan + filter + advance + breaking_pass + publish +
         eddy_transpose;
}

std::size_t BoussinesqSolver::memory_bytes() const {
  const Implementation& s = *implementation_;
  std::size_t bytes = 0;
  auto add = [&bytes](const auto& values) { bytes += values.capacity() * sizeof(values[0]); };
  for (const auto* v : {&s.eta, &s.eta_previous_t, &s.flux_x, &s.flux_y, &s.flux_x_increment, &s.flux_y_increment,
                        &s.breaking_start_s, &s.eta_t, &s.eta_star, &s.eta_next, &s.eta_base, &s.flux_x_new,
                        &s.flux_y_new, &s.tangential_half, &s.tangential_rate, &s.flux_guess, &s.eta_pass_t})
    add(*v);
  add(s.eddy_viscosity);
  add(s.eddy_t);
  add(s.breaking_strength_t);
  for (const auto* v : {&s.dispersive, &s.dispersive_t, &s.wet_cells, &s.filterable_x, &s.filterable_y}) add(*v);
  for (const auto* v : {&s.sponge_cells, &s.sponge_faces_x, &s.sponge_faces_y}) add(*v);
  add(s.sponge_target_x);
  add(s.sponge_target_y);
  for (const StaticFrame* frame : {&s.frame_x, &s.frame_y}) {
    add(frame->depth_m);
    add(frame->porosity);
    add(frame->stone_diameter_ratio);
    add(frame->inverse_porosity);
    add(frame->face_dispersion_weight);
    add(frame->block_is_porous);
  }
  add(s.eta_output.values());
  add(s.breaking_output.values());
  if (s.nonlinear) bytes += s.nonlinear->memory_bytes();
  if (s.roller) bytes += s.roller->memory_bytes();
  for (const auto* v : {&s.surf_zone_cells, &s.surf_zone_scratch, &s.surf_zone_x, &s.surf_zone_y}) add(*v);
  for (const SweepScratch& scratch : s.scratch) bytes += scratch.memory_bytes();
  return bytes;
}

double BoussinesqSolver::water_volume_m3() const {
  // Sum of n h dx dy in a fixed order (deterministic).
  const Implementation& s = *implementation_;
  double volume = 0.0;
  for (std::size_t i = 0; i < s.eta.size(); ++i)
    if (s.frame_y.inverse_porosity[i] > 0.0) volume += (s.frame_y.depth_m[i] + s.eta[i]) / s.frame_y.inverse_porosity[i];
  return volume * s.dx * s.dy;
}

}  // namespace nearshore::boussinesq
