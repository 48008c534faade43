#pragma once
// The solver's state and work arrays, shared by its translation units (solver_setup.cpp: the
// construction; boussinesq_solver.cpp: the step; boussinesq_state.cpp: save and load). Private to
// boussinesq/.
#include <cstdint>
#include <memory>
#include <vector>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "boussinesq_source.hpp"
#include "boussinesq_sweep.hpp"
#include "nearshore/boussinesq/boussinesq_solver.hpp"
#include "nearshore/core/hash.hpp"
#include "nonlinear_dispersion.hpp"
#include "shapiro_filter.hpp"
#include "surface_roller.hpp"

namespace nearshore::boussinesq {

using detail::StaticFrame;
using detail::SweepScratch;

/// XXH64 (core/hash.hpp) of `size` bytes, chained through `seed`: the state checksum and the
/// parameter fingerprint.
inline std::uint64_t hash_bytes(const void* data, std::size_t size, std::uint64_t seed = 0) {
  return xxh64(std::span(static_cast<const std::byte*>(data), size), seed);
}

struct BoussinesqSolver::Implementation {
  GridGeometry geometry;
  SolverParameters parameters;
  int nx = 0, ny = 0;
  double dx = 1.0, dy = 1.0, dt = 0.0, time_s = 0.0;  // cell sizes along x and y (dy = dx: square cells)
  long step_count = 0;
  std::uint64_t fingerprint = 0;

  // frame_x: the x sweep's layout (transposed, columns slow); frame_y: the natural layout.
  StaticFrame frame_x, frame_y;
  detail::SweepConstants constants;
  std::unique_ptr<detail::SourceFunction> source;

  // Every array below costs bytes per cell; docs/solver.md ("Memory") lists them with their use
  // and precision, and BoussinesqSolver::resident_bytes_per_cell() counts them.
  // State. eta, Q and the cell fields in the natural layout (row-major, index r * nx + c);
  // P in the x sweep's layout (index f * ny + r); eta^{n-1} transposed (only the x sweep uses it).
  std::vector<double> eta, eta_previous_t, flux_x, flux_y, flux_x_increment, flux_y_increment;
  std::vector<detail::EddyViscosity> eddy_viscosity;
  std::vector<double> breaking_start_s;  // time, s: double, a bake runs for days of model time
  // Whether eddy_viscosity may hold a non-zero value; when not, eddy_t is all zeros and the
  // transpose is skipped (most of a bake's steps break nowhere, laboratory flumes never).
  bool eddy_viscosity_active = true;
  // BreakingParameters::Model::kRoller: the surface roller (surface_roller.hpp); its start times
  // are breaking_start_s, its indicator breaking_output. roller_active: a roller exists at t^n,
  // so its force acts in this step.
  std::unique_ptr<detail::SurfaceRoller> roller;
  bool roller_active = false;
  // Equations::kFullyNonlinear: the explicit remainder of the fully nonlinear dispersive terms and
  // its history (nonlinear_dispersion.hpp); null for the seed's equations.
  std::unique_ptr<detail::NonlinearDispersion> nonlinear;
  // Work arrays (suffix _t: x sweep layout). Shared between the sweeps where their lives do not
  // overlap: eta_base is E of whichever sweep runs (in its layout), tangential_half/_rate the other
  // flux at t^{n+1/2} in the running sweep's layout; eta_next doubles as scratch for eta^{n-1}
  // before the x sweep writes it (step()). Both sweeps write eta in the natural layout.
  std::vector<double> eta_t, eta_star, eta_next, eta_base;
  std::vector<double> flux_x_new, flux_y_new, tangential_half, tangential_rate;
  // Only when adi_passes > 1: the previous pass's flux increment and its eta^{n+1} transposed.
  std::vector<double> flux_guess, eta_pass_t;
  std::vector<detail::EddyViscosity> eddy_t;
  // Equations::kFullyNonlinear: the breaking strength B in the x sweep's layout, by which the fully
  // nonlinear terms fade where waves break (BreakingParameters::fade_fully_nonlinear_terms; the y
  // sweep and the remainder read breaking_output). Transposed like eddy_t while cells break, all
  // zeros otherwise, and all zeros for good when the terms do not fade (fade_nonlinear false).
  std::vector<float> breaking_strength_t;
  bool fade_nonlinear = false;
  // Masks, 0 or 1: the dispersion mask of eta^n per layout (mark_dispersive), its wet-cell
  // scratch, and the grid-scale filter's masks of the P and Q faces.
  std::vector<unsigned char> dispersive, dispersive_t, wet_cells, filterable_x, filterable_y;
  detail::ShapiroFilter flux_filter;  // order solver.shapiro_filter_order, its stencil built once
  // The roller's surf-zone filter (BreakingParameters::roller_filter_order) and its masks: cells near
  // a roller (and a scratch for the dilation), P and Q faces it may change. Empty without a roller.
  detail::ShapiroFilter surf_zone_filter{0};
  std::vector<unsigned char> surf_zone_cells, surf_zone_scratch, surf_zone_x, surf_zone_y;
  // Sponge damping factors per step (docs/solver.md "Sponge layers"), only where they are not 1:
  // memory in proportion to the layers, not to the grid.
  struct SpongePoint {
    std::size_t index;  // cell (natural layout), P face (px) or Q face (qy)
    double factor;      // 1 / (1 + sigma dt)
  };
  std::vector<SpongePoint> sponge_cells, sponge_faces_x, sponge_faces_y;
  // With an imposed current (SolverParameters::current): the flux each sponge face relaxes towards
  // (parallel to sponge_faces_x / _y); empty without one (the sponges relax towards rest).
  std::vector<double> sponge_target_x, sponge_target_y;
  // The still-water level above the grid's (BoussinesqSolver::set_still_water_level), metres: the
  // sponges' target for eta.
  double still_water_level_m = 0.0;
  tbb::enumerable_thread_specific<SweepScratch> scratch;
  // Output rasters. breaking_output is also the state's breaking strength B (0..1, float).
  Raster<float> eta_output, breaking_output;

  std::size_t px(int f, int r) const { return static_cast<std::size_t>(f) * ny + r; }  // P face west of cell (f, r)
  std::size_t qy(int c, int k) const { return static_cast<std::size_t>(k) * nx + c; }  // Q face south of cell (c, k)

  void sweep(const StaticFrame& frame, const detail::SweepInput& input, const detail::SweepOutput& output) {
    // One task per block (simple_partitioner): a sweep has only 13 blocks on the Berkhoff grid's x
    // sweep, and whole-block stealing balances the two cores better than grouped chunks.
    const int blocks = (frame.rows + detail::kBlockLines - 1) / detail::kBlockLines;
    tbb::parallel_for(
        tbb::blocked_range<int>(0, blocks, 1),
        [&](const tbb::blocked_range<int>& range) {
          SweepScratch& s = scratch.local();
          const std::size_t needed = static_cast<std::size_t>(frame.cols + 5) * detail::kBlockLines;
          if (s.upper.size() < needed) s.resize(frame.cols);
          for (int block = range.begin(); block < range.end(); ++block) {
            const int begin = block * detail::kBlockLines;
            detail::sweep_lines(frame, constants, input, output, begin, std::min(frame.rows, begin + detail::kBlockLines), s);
          }
        },
        tbb::simple_partitioner());
  }

  // Construction (solver_setup.cpp), in the order the constructor runs the steps: each checks what
  // it takes (the errors come in this order) and fills its part of the members above.
  // The harbour grid's cells as the solver takes them, only while it is built (natural layout).
  struct CellFields {
    std::vector<float> depth_m, porosity, stone_diameter_ratio;  // depth capped at the effective depth
    double max_depth_m = 0.0;                                    // the deepest cell, metres
  };
  void take_grid(const HarbourGrid& harbour, const SolverParameters& solver_parameters);
  CellFields read_cell_fields(const HarbourGrid& harbour) const;
  std::vector<float> read_stone_diameter_ratios(const HarbourGrid& harbour) const;
  void choose_time_step(double max_depth_m);
  void check_scheme_parameters() const;
  void take_fingerprint(const std::vector<float>& depth_m);
  void set_sweep_constants();
  void build_frames(CellFields cells, double peak_w);
  void build_sponges();
  void allocate_state_and_work_arrays();
  void set_up_current();
  // The imposed current's flux u d (v d) at x face (f, r) (y face (c, k)), m^2/s: 0 unless both cells
  // of the face are open water; the grid's edge faces take their one cell.
  double current_flux_x_m2_s(int f, int r) const;
  double current_flux_y_m2_s(int c, int k) const;
  void set_current_fluxes();  // every face's flux to the current's (at rest: 0)
  void set_up_fully_nonlinear_terms();
  void set_up_surface_roller(const WaveMaker& wave_maker, double peak_w);

  void mark_dispersive(const StaticFrame& frame, const double* eta_frame, unsigned char* mask);
  void step();
  void repair_negative_depths();
  void filter_grid_scale_fluxes();
  void filter_surf_zone_fluxes();
  void apply_sponges();
  void update_breaking(const std::vector<double>& eta_old);
  void add_roller_force();
  void publish();
};

}  // namespace nearshore::boussinesq
