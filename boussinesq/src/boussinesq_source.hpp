#pragma once
// Internal wave generation by a source function in the mass equation (Wei, Kirby & Sun 1999),
// with the source amplitude derived for the Madsen & Sorensen (1992) equations the solver uses
// (docs/solver.md, "Wave maker"). Waves leave the source line on both sides; the ones heading
// for the `facing` side are absorbed by the sponge behind the line, and reflected waves coming
// back cross the line unhindered.
#include <vector>

#include "nearshore/boussinesq/model_dispersion.hpp"
#include "nearshore/boussinesq/solver_parameters.hpp"
#include "nearshore/core/raster.hpp"  // GridGeometry

namespace nearshore::boussinesq::detail {

class SourceFunction {
 public:
  /// depth_m: cell depths (cols x rows, row-major), the master orientation of the solver.
  /// `parameters`: the equations whose waves the line makes (B, and for second-order generation
  /// which nonlinear terms).
  SourceFunction(const WaveMaker& wave_maker, const GridGeometry& geometry, const std::vector<float>& depth_m,
                 const SolverParameters& parameters);
  bool empty() const { return components_.empty(); }
  /// eta_base[cell] += dt * S(x, y, time_s) for every cell of the source strip; cell (column c,
  /// row r) is eta_base[c * x_stride + r * y_stride].
  void add(double time_s, double dt, double* eta_base, std::size_t x_stride, std::size_t y_stride);
  /// The components actually generated (after decomposition of a time series), for the record.
  std::size_t component_count() const { return components_.size(); }

 private:
  struct Component {
    double amplitude_m;    // the requested amplitude a at the line
    double angular_frequency_rad_s;
    double tangential_wavenumber_rad_m;  // l: wavenumber along the source line
    double phase_rad;      // psi: phase of the source at tangential coordinate 0
    double strength_m_s = 0.0;  // D of Wei et al. (1999), metres per second, for time_step_s_
    double current_along_m_s = 0.0;  // the imposed current's component along the wave (SolverParameters::current)
  };
  /// D for a component on this grid and time step: the discrete transfer of the scheme (docs/solver.md,
  /// "Wave maker"), which tends to the continuous equations' as dx, dt -> 0.
  double discrete_strength_m_s(const Component& component, double dt) const;
  /// On a current: D per metre of radiated amplitude for a wave of (grid) frequency w_grid and
  /// wavenumber l along the line, with U_along the current along its travel and U_normal the
  /// current's component normal to the line along its travel (the residue of "Currents").
  /// The pole of the grid's forced response at wavenumber k (wavenumber l along the line): kappa_n,
  /// its slope d kappa_n / d k_n, M(k^2) and I, the Gaussian's transform at k_n (discrete_strength_m_s).
  struct Pole {
    double wavenumber_rad_m = 0.0, kappa_n = 0.0, slope = 1.0, M = 1.0, I = 0.0;
  };
  Pole pole(double k, double l) const;
  double strength_per_amplitude_in_current(double w_grid, double l, double U_along, double U_normal) const;
  /// On a current: the amplitude of the twin a component of frequency w and wavenumber l along the
  /// line radiates behind the line (the wave the other way, the current U_twin_along along its
  /// travel) per metre of the component's amplitude; 0 when the current blocks the twin.
  double twin_amplitude_ratio(double w, double l, double U_along, double U_twin_along) const;
  std::vector<Component> components_;
  double time_step_s_ = 0.0;             // the dt the strengths were computed for (set on first add)
  double depth_m_ = 0.0, dispersion_coefficient_ = 1.0 / 15.0, line_index_ = 0.0;
  bool normal_is_x_ = true;
  bool current_ = false;                 // an imposed current (SolverParameters::current)
  double current_normal_m_s_ = 0.0;      // its component along the travel direction normal to the line
  int strip_begin_ = 0, strip_end_ = 0;  // cell indices along the normal axis, [begin, end)
  int span_begin_ = 0, span_end_ = 0;    // cell indices along the line, [begin, end): WaveMaker's span
  std::vector<double> profile_;          // Gaussian g(s - s_line) per strip index
  int cols_ = 0, rows_ = 0;
  double tangential_origin_m_ = 0.0, ramp_time_s_ = 0.0;
  double spacing_m_ = 1.0;             // cell size normal to the line (x for kWest/kEast), metres
  double tangential_spacing_m_ = 1.0;  // cell size along the line, metres
  std::vector<unsigned char> water_;     // 1 where the strip cell is water, strip x tangential
  std::vector<double> line_;             // sum over components along the line (scratch)
};

}  // namespace nearshore::boussinesq::detail
