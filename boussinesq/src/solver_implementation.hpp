#pragma once
// The solver's state and work arrays, shared by its translation units (boussinesq_solver.cpp: the
// step; boussinesq_state.cpp: save and load). Private to boussinesq/.
#include <cstdint>
#include <memory>
#include <vector>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "boussinesq_source.hpp"
#include "boussinesq_sweep.hpp"
#include "nearshore/boussinesq/boussinesq_solver.hpp"
#include "nearshore/core/hash.hpp"
#include "shapiro_filter.hpp"

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
  double dx = 1.0, dt = 0.0, time_s = 0.0;
  long step_count = 0;
  std::uint64_t fingerprint = 0;

  // frame_x: the x sweep's layout (transposed, columns slow); frame_y: the natural layout.
  StaticFrame frame_x, frame_y;
  detail::SweepConstants constants;
  std::unique_ptr<detail::SourceFunction> source;

  // State. eta, Q and the cell fields in the natural layout (row-major, index r * nx + c);
  // P in the x sweep's layout (index f * ny + r); eta^{n-1} transposed (only the x sweep uses it).
  std::vector<double> eta, eta_previous_t, flux_x, flux_y, flux_x_increment, flux_y_increment;
  std::vector<double> eddy_viscosity, breaking_start_s, breaking_strength;
  // Whether eddy_viscosity may hold a non-zero value; when not, eddy_t is all zeros and the
  // transpose is skipped (most of a bake's steps break nowhere, laboratory flumes never).
  bool eddy_viscosity_active = true;
  // Work arrays (suffix _t: x sweep layout).
  std::vector<double> eta_t, eta_base_t, eta_across_t, eta_star_t, flux_x_across, flux_x_new,
      tangential_half_t, tangential_rate_t, eddy_t;
  std::vector<double> eta_star, eta_across, flux_y_across, flux_x_half, flux_x_rate, eta_next, flux_y_new;
  std::vector<double> flux_x_guess, flux_y_guess, eta_base;
  std::vector<double> dispersive, dispersive_t, wet_cells;
  std::vector<double> filterable_x, filterable_y;  // grid-scale filter masks (P and Q faces), 0 or 1
  detail::ShapiroFilter flux_filter;  // order solver.shapiro_filter_order, its stencil built once
  std::vector<double> sponge_cell, sponge_face_x, sponge_face_y;  // damping factor per step (1 = none)
  tbb::enumerable_thread_specific<SweepScratch> scratch;
  // Output rasters.
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

  void mark_dispersive(const StaticFrame& frame, const double* eta_frame, double* mask);
  void step();
  void repair_negative_depths();
  void filter_grid_scale_fluxes();
  void apply_sponges();
  void update_breaking(const std::vector<double>& eta_old);
  void publish();
};

}  // namespace nearshore::boussinesq
