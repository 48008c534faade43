#include "boussinesq_source.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <sstream>

#include "nearshore/boussinesq/model_nonlinear.hpp"
#include "nearshore/core/error.hpp"

namespace nearshore::boussinesq::detail {

using namespace nearshore::ocean;  // wave components, sea states, linear waves


namespace {

double ramp(double time_s, double ramp_time_s) {
  if (ramp_time_s <= 0.0 || time_s >= ramp_time_s) return 1.0;
  if (time_s <= 0.0) return 0.0;
  return 0.5 * (1.0 - std::cos(std::numbers::pi * time_s / ramp_time_s));
}

// A user time series eta(t) as normally incident components: the discrete Fourier transform of
// the series, resampled linearly to uniform spacing. The series repeats with its length.
std::vector<WaveComponent> components_from_series(const WaveMaker& maker, double direction_rad) {
  const auto& t = maker.series_time_s;
  const auto& e = maker.series_elevation_m;
  if (t.size() != e.size() || t.size() < 4)
    throw Error("wave maker time series", "needs at least 4 samples with as many times as elevations (got " +
                                              std::to_string(t.size()) + " times, " + std::to_string(e.size()) + " elevations)",
                "give series_time_s and series_elevation_m of equal length");
  for (std::size_t i = 1; i < t.size(); ++i)
    if (!(t[i] > t[i - 1]))
      throw Error("wave maker time series", "time does not increase at sample " + std::to_string(i) + " (t=" +
                                                std::to_string(t[i]) + " s)", "sort the samples by time and remove duplicates");
  const std::size_t n = t.size();
  const double span = t.back() - t.front();
  const double spacing = span / static_cast<double>(n - 1);
  std::vector<double> uniform(n);
  for (std::size_t i = 0, j = 0; i < n; ++i) {
    const double ti = t.front() + spacing * static_cast<double>(i);
    while (j + 2 < n && t[j + 1] < ti) ++j;
    const double a = std::clamp((ti - t[j]) / (t[j + 1] - t[j]), 0.0, 1.0);
    uniform[i] = e[j] + a * (e[j + 1] - e[j]);
  }
  const double period = spacing * static_cast<double>(n);
  std::vector<WaveComponent> components;
  for (std::size_t m = 1; m < n / 2; ++m) {
    std::complex<double> sum = 0.0;
    const double w = 2.0 * std::numbers::pi * static_cast<double>(m) / period;
    for (std::size_t i = 0; i < n; ++i) sum += uniform[i] * std::polar(1.0, -w * spacing * static_cast<double>(i));
    const double amplitude = 2.0 * std::abs(sum) / static_cast<double>(n);
    // eta(t) = a cos(w (t - t0) + arg X) = a cos(-w t + phi) with phi = w t0 - arg X.
    components.push_back({amplitude, w, direction_rad, w * t.front() - std::arg(sum)});
  }
  return components;
}

}  // namespace

SourceFunction::SourceFunction(const WaveMaker& maker, const GridGeometry& geometry, const std::vector<float>& depth,
                               const SolverParameters& parameters) {
  const double B = parameters.dispersion_coefficient;
  if (maker.kind != WaveMaker::Kind::kComponents && maker.kind != WaveMaker::Kind::kTimeSeries) return;
  cols_ = geometry.columns;
  rows_ = geometry.rows;
  ramp_time_s_ = maker.ramp_time_s;
  normal_is_x_ = maker.facing == Side::kWest || maker.facing == Side::kEast;
  // Rectangular cells: the strip's profile and its transform I use the cell size normal to the
  // line, the phase along the line the size along it.
  spacing_m_ = normal_is_x_ ? geometry.spacing_x_m() : geometry.spacing_y_m();
  tangential_spacing_m_ = normal_is_x_ ? geometry.spacing_y_m() : geometry.spacing_x_m();
  const double travel_sign = (maker.facing == Side::kWest || maker.facing == Side::kSouth) ? 1.0 : -1.0;
  const int normal_count = normal_is_x_ ? cols_ : rows_, tangential_count = normal_is_x_ ? rows_ : cols_;
  const double normal_origin = normal_is_x_ ? geometry.origin_x_m : geometry.origin_y_m;
  tangential_origin_m_ = normal_is_x_ ? geometry.origin_y_m : geometry.origin_x_m;
  const double line_m = maker.source_line_m;
  const double line_index = (line_m - normal_origin) / spacing_m_ - 0.5;  // fractional cell index
  if (line_index < 0.0 || line_index > normal_count - 1.0) {
    std::ostringstream problem;
    problem << "source_line_m = " << line_m << " m lies outside the grid (" << normal_origin << " .. "
            << normal_origin + normal_count * spacing_m_ << " m along " << (normal_is_x_ ? "x" : "y") << ")";
    throw Error("wave maker", problem.str(), "put the source line inside the grid, in front of the sponge");
  }
  // The span the source acts on (WaveMaker::span_begin_cell; the whole line by default).
  span_begin_ = std::clamp(maker.span_begin_cell, 0, tangential_count);
  span_end_ = std::clamp(maker.span_end_cell, span_begin_, tangential_count);
  // Still-water depth at the source line: the mean over the wet cells of the span.
  double depth_sum = 0.0;
  int wet = 0;
  const int line_cell = static_cast<int>(std::lround(line_index));
  for (int t = span_begin_; t < span_end_; ++t) {
    const double d = normal_is_x_ ? depth[static_cast<std::size_t>(t) * cols_ + line_cell]
                                  : depth[static_cast<std::size_t>(line_cell) * cols_ + t];
    if (d > 0.0) { depth_sum += d; ++wet; }
  }
  if (wet == 0)
    throw Error("wave maker",
                "the source line at " + std::to_string(line_m) + " m runs over land only" +
                    (span_begin_ > 0 || span_end_ < tangential_count
                         ? " in its span of cells " + std::to_string(span_begin_) + " to " + std::to_string(span_end_ - 1)
                         : std::string()),
                "move source_line_m into open water");
  const double d = depth_sum / wet;

  const double mean_direction = normal_is_x_ ? (travel_sign > 0 ? 0.0 : std::numbers::pi)
                                             : (travel_sign > 0 ? 0.5 * std::numbers::pi : -0.5 * std::numbers::pi);
  std::vector<WaveComponent> waves = maker.kind == WaveMaker::Kind::kComponents
                                         ? maker.sea_state.components
                                         : components_from_series(maker, mean_direction);
  if (waves.empty()) return;
  // The largest component: its amplitude is the scale below which components are not made.
  const auto peak = std::max_element(waves.begin(), waves.end(),
                                     [](const WaveComponent& a, const WaveComponent& b) { return a.amplitude_m < b.amplitude_m; });
  // On a current (SolverParameters::current) every wave has its Doppler-shifted wavenumber: the
  // frequency is the absolute one, the one the line's source oscillates at.
  const ImposedCurrent& current = parameters.current;
  current_ = current.any();
  current_normal_m_s_ = travel_sign * (normal_is_x_ ? current.velocity_x_m_s : current.velocity_y_m_s);
  // The current's component along a wave's direction of travel (k.U / |k|).
  auto current_along_m_s = [&](double direction_rad) {
    return current.velocity_x_m_s * std::cos(direction_rad) + current.velocity_y_m_s * std::sin(direction_rad);
  };
  // The same along a direction mirrored in the line: the source's twin, the wave of the same
  // frequency and wavenumber along the line that it radiates behind the line.
  auto twin_current_along = [&](double direction_rad) {
    return current_along_m_s(normal_is_x_ ? std::numbers::pi - direction_rad : -direction_rad);
  };
  auto wavenumber = [&](double w, double direction_rad) {
    if (!current_) return boussinesq_wavenumber(w, d, B);
    return boussinesq_wavenumber_in_current(w, d, B, current_along_m_s(direction_rad));  // 0: blocked
  };
  auto blocked = [&](double w) {
    std::ostringstream problem;
    problem << "the current (" << current.velocity_x_m_s << ", " << current.velocity_y_m_s << ") m/s blocks a wave of w=" << w
            << " rad/s at the source line (depth " << d << " m): its group speed is below the current against it";
    return Error("wave maker", problem.str(), "weaken the current, or drop the band's highest frequencies (the shortest waves are blocked first)");
  };
  const double peak_k = wavenumber(peak->angular_frequency_rad_s, peak->direction_rad);
  if (current_ && peak_k == 0.0) throw blocked(peak->angular_frequency_rad_s);
  const double largest = peak->amplitude_m;
  // Which components the line makes (the loop below): a time series' harmonics beyond the
  // equations' range (k d > 3), or blocked by a current, are not generated.
  auto significant = [&](const WaveComponent& wave) {
    return wave.amplitude_m > 1e-6 * largest && wave.angular_frequency_rad_s > 0.0;
  };
  auto in_range = [&](double k) { return maker.kind != WaveMaker::Kind::kTimeSeries || (k * d <= 3.0 && k != 0.0); };
  // Gaussian width from the shortest wave the line makes: beta = 20 / L^2 (Wei, Kirby & Sun 1999's
  // choice for one wave; the e-folding half-width L/4.5 keeps the source compact yet resolved at 20
  // cells per wavelength). The transfer I falls as exp(-k^2 / 4 beta), so each component's strength
  // D grows by its inverse, and D is also the size of the source's near field, the local response
  // that does not radiate: sized for the peak, a component of k = 4 k_p needs 2600 times the
  // strength per amplitude. A measured record's DFT carries its noise floor at full strength up to
  // k d = 3: Dingemans' gauge-1 record (docs/validation.md) has 0.3 mm components up to 4.5 times the
  // peak's wavenumber, which the peak's width made into a near field of 0.8 m, drying the 0.8 m deep
  // flume at the line. Sized for the shortest, every component's transfer is at least e^-0.49 = 0.61
  // of the Gaussian's full weight, and no component needs a near field much larger than its wave.
  // One wave (a regular maker) gets the width it always had.
  double shortest_k = peak_k;
  for (const WaveComponent& wave : waves) {
    if (!significant(wave)) continue;
    const double k = wavenumber(wave.angular_frequency_rad_s, wave.direction_rad);
    if (in_range(k)) shortest_k = std::max(shortest_k, k);
  }
  const double shortest_length = 2.0 * std::numbers::pi / shortest_k;
  const double beta = 20.0 / (shortest_length * shortest_length);
  const double half_width = 3.0 / std::sqrt(beta);
  strip_begin_ = std::max(0, static_cast<int>(std::floor(line_index - half_width / spacing_m_)));
  strip_end_ = std::min(normal_count, static_cast<int>(std::ceil(line_index + half_width / spacing_m_)) + 1);
  profile_.resize(static_cast<std::size_t>(strip_end_ - strip_begin_));
  for (int i = strip_begin_; i < strip_end_; ++i) {
    const double s = (i - line_index) * spacing_m_;
    profile_[static_cast<std::size_t>(i - strip_begin_)] = std::exp(-beta * s * s);
  }

  depth_m_ = d;
  dispersion_coefficient_ = B;
  line_index_ = line_index;
  for (const WaveComponent& wave : waves) {
    if (!significant(wave)) continue;
    const double w = wave.angular_frequency_rad_s;
    const double k = wavenumber(w, wave.direction_rad);
    if (!in_range(k)) continue;
    if (current_ && k == 0.0) throw blocked(w);
    // On a current a wave the still water carries can be too short for the equations: against
    // 0.5 m/s over 0.5 m the 1 s wave has k d = 5.7 (2.1 in still water). The line then barely
    // excites it ahead and excites its long twin behind the line in full (twin_amplitude_ratio): a
    // 1 mm component of 1 s beside a 5 mm one of 2 s broke the run within 1.5 s. Refused like a
    // blocked one (a time series' such harmonics are dropped above).
    if (current_ && k * d > kLargestCarriedKd) {
      std::ostringstream problem;
      problem << "the current (" << current.velocity_x_m_s << ", " << current.velocity_y_m_s << ") m/s shortens a wave of w=" << w
              << " rad/s at the source line (depth " << d << " m) to k d = " << k * d << ", beyond the equations' range (k d <= "
              << kLargestCarriedKd << ")";
      throw Error("wave maker", problem.str(), "drop the band's highest frequencies, or weaken the current against the waves");
    }
    const double kx = k * std::cos(wave.direction_rad), ky = k * std::sin(wave.direction_rad);
    const double k_normal = normal_is_x_ ? kx : ky, k_tangential = normal_is_x_ ? ky : kx;
    if (k_normal * travel_sign < 0.2 * k) {
      std::ostringstream problem;
      problem << "a component (w=" << w << " rad/s, direction " << wave.direction_rad * 180.0 / std::numbers::pi
              << " deg) does not travel away from the " << (normal_is_x_ ? (travel_sign > 0 ? "west" : "east") : (travel_sign > 0 ? "south" : "north"))
              << " side within 78 deg of its normal";
      throw Error("wave maker", problem.str(), "turn the source line (facing) or limit the directional spread");
    }
    // A component's phase phi is the field's, eta = a cos(kx x + ky y - w t + phi) (wave_component.hpp),
    // so at the line s = line_m the source's phase at tangential 0 is phi + k_n line_m. A time
    // series is eta(t) measured at the line itself (WaveMaker::series_elevation_m): its phases
    // already are the line's. Adding k_n line_m to them reproduced the record at s = 0 instead, every
    // component moved by its own k_n line_m: Dingemans' gauge-1 record, driven on its gauge's line
    // 13.04 m from the grid's edge, came out 0.75 s early at the line (a 2.857 s wave moved by
    // 0.84 rad/m x 13.04 m), its harmonics each by another shift.
    const double phase = wave.phase_rad + (maker.kind == WaveMaker::Kind::kTimeSeries ? 0.0 : k_normal * line_m);
    // The strength D needs the time step, which the solver passes to add(): computed there.
    components_.push_back({wave.amplitude_m, w, k_tangential, phase, 0.0, current_along_m_s(wave.direction_rad)});
  }
  // Nonlinear generation (WaveMaker::second_order): the regular wave's bound harmonics,
  // eta_n = a_n cos n(k.x - w t + phi), each radiated as a free wave at n w with its phase at the
  // line, cancel the free waves of the opposite sign that the first harmonic alone sheds where it
  // sets in. a_n from the steady wave of the equations the solver integrates, at the line's depth,
  // with the first harmonic chosen so that its crest-to-trough height is the requested 2 a.
  if (maker.second_order && maker.kind == WaveMaker::Kind::kComponents && components_.size() == 1) {
    Component& primary = components_.front();
    // On a current the steady wave is the same in the frame moving with the water (the equations'
    // Galilean invariance), at the Doppler-shifted k.
    const double w = primary.angular_frequency_rad_s,
                 k = current_ ? boussinesq_wavenumber_in_current(w, d, B, primary.current_along_m_s)
                              : boussinesq_wavenumber(w, d, B);
    const double height_m = 2.0 * primary.amplitude_m;
    auto steady = [&](double a) {
      return boussinesq_steady_wave(a, k, d, B, parameters.dispersion_depth, 8, parameters.equations).harmonics_m;
    };
    auto crest_to_trough = [](const std::vector<double>& harmonics) {  // eta(0) - eta(pi)
      double h = 0.0;
      for (std::size_t n = 0; n < harmonics.size(); n += 2) h += 2.0 * harmonics[n];
      return h;
    };
    try {
      double a = primary.amplitude_m;
      for (int iteration = 0; iteration < 6; ++iteration) a *= height_m / crest_to_trough(steady(a));
      const std::vector<double> harmonics = steady(a);
      primary.amplitude_m = a;
      // The second harmonic only: second-order theory says the spurious free wave is minus the bound
      // one; at third order the free second harmonic interacts with the first too, and radiating
      // the bound third harmonic the same way doubled the flat-flume beat instead of removing it.
      // A harmonic beyond the equations' range (k d > 3) is not carried.
      // On a current (docs/solver.md, "Currents") the free harmonic at 2 w has its own Doppler-shifted
      // wavenumber, far from the bound 2 k against the current (k d = 5.7 for T = 2 s against
      // 0.5 m/s over 0.5 m, where the bound one has 2.3): the range is checked on it. And the line
      // radiates each component both ways: behind it goes the twin (same frequency, the current
      // the other way along it), whose amplitude is the component's times the ratio of their
      // transfers (twin_amplitude_ratio). Against a current the free harmonic is short and the
      // Gaussian, sized for the first harmonic, barely excites it (its transform ~ e^-12 in that
      // flume), while the long twin going downstream is excited in full: 5700 times the harmonic,
      // a 0.33 m wave at 2 w behind the line for a = 5 mm, which broke the run within the ramp. The
      // correction is radiated only while its twin stays smaller than the wave the line is asked
      // for (in still water the twin is the harmonic itself, ratio 1).
      const double l2 = 2.0 * primary.tangential_wavenumber_rad_m;
      const double k2 = current_ ? boussinesq_wavenumber_in_current(2.0 * w, d, B, primary.current_along_m_s)
                                 : boussinesq_wavenumber(2.0 * w, d, B);
      bool radiate = k2 * d <= 3.0 && harmonics[1] > 0.0;
      if (current_)
        radiate = radiate && k2 > 0.0 &&
                  harmonics[1] * twin_amplitude_ratio(2.0 * w, l2, primary.current_along_m_s, twin_current_along(peak->direction_rad)) <=
                      primary.amplitude_m;
      if (radiate)
        components_.push_back({harmonics[1], 2.0 * w, l2, 2.0 * primary.phase_rad, 0.0, primary.current_along_m_s});
    } catch (const Error&) {
      // Steeper than the equations' steady waves reach: the first harmonic alone, as requested.
    }
  }
  line_.assign(static_cast<std::size_t>(tangential_count), 0.0);
  // The source acts on water only: cells of the strip on land get none (no water made on land),
  // and on its span only (WaveMaker::span_begin_cell).
  water_.assign(profile_.size() * static_cast<std::size_t>(tangential_count), 0);
  for (int i = strip_begin_; i < strip_end_; ++i)
    for (int j = span_begin_; j < span_end_; ++j) {
      const std::size_t cell = normal_is_x_ ? static_cast<std::size_t>(j) * cols_ + i : static_cast<std::size_t>(i) * cols_ + j;
      water_[static_cast<std::size_t>(i - strip_begin_) * tangential_count + j] = depth[cell] > 0.0;
    }
}

// Source amplitude (docs/solver.md, "Wave maker"). For the continuous Madsen & Sorensen equations
// (flat bed at the line's depth d) a source S = D g(s) cos(l t - w t + psi) radiates
//   A = D I w M(k^2) / (2 |k_n| F'(k^2)),  M(s) = 1 + (B+1/3) d^2 s,  G(s) = g d (1 + B d^2 s),
//   F(s) = s G(s) - w^2 M(s),  F'(s) = G(s) + s g d B d^2 - w^2 (B+1/3) d^2,
// the residue of the forced response at the pole k (Wei, Kirby & Sun 1999's derivation, carried out
// for these equations), with I the transform of g at k_n. On the grid the same derivation runs with the
// scheme's operators instead of the derivatives (issue 19: +3.9 % at 10 cells per wavelength with
// the continuous A, +1.0 % at 24):
//  * space: on the staggered grid every first difference of a Fourier mode exp(i k x) is i kappa,
//    kappa = 2 sin(k dx / 2) / dx, and every three-point second difference -kappa^2, so the
//    discrete dispersion relation is F(kappa_n^2 + kappa_t^2) = 0 and the pole lies at the k_n whose
//    kappa_n solves it, k_n = (2 / dx) asin(kappa_n dx / 2) (longer than the continuous one). The
//    residue's derivative d s / d k_n = 2 kappa_n cos(k_n dx / 2) replaces 2 k_n, and I is the
//    transform of the Gaussian, sampled on the cells, at that k_n.
//  * time: the mass equation is Crank-Nicolson with the source at t^{n+1/2} (boussinesq_solver.cpp):
//    for a mode exp(-i w t) it reads -i w~ eta + ... = S / cos(w dt / 2), w~ = (2 / dt) tan(w dt / 2),
//    and the time-centred momentum equation likewise carries w~. So the grid's wave obeys the
//    dispersion relation at w~, and the source acts 1 / cos(w dt / 2) stronger.
// Both tend to the continuous transfer as dx, dt -> 0.
double SourceFunction::discrete_strength_m_s(const Component& component, double dt) const {
  const double w = component.angular_frequency_rad_s;
  const double half_phase_step = 0.5 * w * dt;
  // Fewer than pi steps per period (w dt / 2 >= 1): the grid resolves no such wave in time; the
  // continuous transfer is kept for it rather than a tangent near its pole.
  const double w_grid = half_phase_step < 1.0 ? 2.0 * std::tan(half_phase_step) / dt : w;
  const double time_factor = half_phase_step < 1.0 ? std::cos(half_phase_step) : 1.0;
  if (current_)
    return component.amplitude_m * time_factor *
           strength_per_amplitude_in_current(w_grid, component.tangential_wavenumber_rad_m, component.current_along_m_s,
                                             current_normal_m_s_);
  const double g = kGravity_m_s2, B = dispersion_coefficient_, d = depth_m_, d2 = d * d;
  const Pole p = pole(boussinesq_wavenumber(w_grid, d, B), component.tangential_wavenumber_rad_m);
  const double s = p.wavenumber_rad_m * p.wavenumber_rad_m;
  const double F_prime = g * d * (1.0 + B * d2 * s) + s * g * d * B * d2 - w_grid * w_grid * (B + 1.0 / 3.0) * d2;
  return component.amplitude_m * time_factor * 2.0 * p.kappa_n * p.slope * F_prime / (w_grid * p.M * p.I);
}

SourceFunction::Pole SourceFunction::pole(double k, double l) const {
  const double B3 = dispersion_coefficient_ + 1.0 / 3.0, d2 = depth_m_ * depth_m_;
  const double s = k * k;
  const double dn = spacing_m_, dl = tangential_spacing_m_;  // cell sizes normal to and along the line
  const double kappa_t = 2.0 * std::sin(0.5 * l * dl) / dl;
  Pole p;
  p.wavenumber_rad_m = k;
  p.kappa_n = std::sqrt(std::max(s - kappa_t * kappa_t, 0.01 * s));
  // A wave shorter than about three cells normal to the line has no discrete pole (kappa dx / 2 -> 1):
  // the grid cannot carry it, and the continuous transfer is kept for it.
  const double sine = 0.5 * p.kappa_n * dn;
  const double k_n = sine < 0.95 ? 2.0 * std::asin(sine) / dn : p.kappa_n;
  p.slope = sine < 0.95 ? std::cos(0.5 * k_n * dn) : 1.0;  // d kappa_n / d k_n
  p.M = 1.0 + B3 * d2 * s;
  for (int i = strip_begin_; i < strip_end_; ++i)
    p.I += profile_[static_cast<std::size_t>(i - strip_begin_)] * std::cos(k_n * (i - line_index_) * dn) * dn;
  return p;
}

// On a current U (docs/solver.md, "Currents"): linearised about P = U d, the flux-form momentum
// equation moves with the water, M D u/Dt + grad(G eta / d) ... = -U S / d (the source adds mass
// without momentum), so the forced response is eta = i S (w_r M - k.U) / (|k|^2 G - w_r^2 M) and its
// residue at the pole k_n is A = D I (w_r M - k.U) / (2 k_n F'_r + 2 U_n w_r M), with F'_r = F' at
// the intrinsic frequency w_r = w - k.U, k the Doppler-shifted wavenumber and U_n the current along
// the travel direction normal to the line (the discrete kappa_n and its slope as above). U = 0
// gives the still-water transfer.
double SourceFunction::twin_amplitude_ratio(double w, double l, double U_along, double U_twin_along) const {
  // A twin the current blocks (its group speed below the current against it) is not radiated.
  if (boussinesq_wavenumber_in_current(w, depth_m_, dispersion_coefficient_, U_twin_along) == 0.0) return 0.0;
  return strength_per_amplitude_in_current(w, l, U_along, current_normal_m_s_) /
         strength_per_amplitude_in_current(w, l, U_twin_along, -current_normal_m_s_);
}

double SourceFunction::strength_per_amplitude_in_current(double w_grid, double l, double U_along, double U_normal) const {
  const double g = kGravity_m_s2, B = dispersion_coefficient_, d = depth_m_, d2 = d * d;
  const Pole p = pole(boussinesq_wavenumber_in_current(w_grid, d, B, U_along), l);
  const double k = p.wavenumber_rad_m, s = k * k, w_r = w_grid - k * U_along;
  const double F_prime_r = g * d * (1.0 + B * d2 * s) + s * g * d * B * d2 - w_r * w_r * (B + 1.0 / 3.0) * d2;
  return (2.0 * p.kappa_n * p.slope * F_prime_r + 2.0 * U_normal * w_r * p.M) / ((w_r * p.M - k * U_along) * p.I);
}

void SourceFunction::add(double time_s, double dt, double* eta_base, std::size_t x_stride, std::size_t y_stride) {
  if (components_.empty()) return;
  if (dt != time_step_s_) {  // the first step (the solver's dt is fixed; a new one recomputes)
    for (Component& c : components_) c.strength_m_s = discrete_strength_m_s(c, dt);
    time_step_s_ = dt;
  }
  const double r = ramp(time_s, ramp_time_s_);
  if (r == 0.0) return;
  std::fill(line_.begin(), line_.end(), 0.0);
  const int tangential_count = static_cast<int>(line_.size());
  // Sum along the line by complex rotation: exp(i (l t_j - w t + psi)) advanced cell by cell.
  for (const Component& c : components_) {
    const double t0 = tangential_origin_m_ + (span_begin_ + 0.5) * tangential_spacing_m_;
    std::complex<double> z = std::polar(c.strength_m_s, c.tangential_wavenumber_rad_m * t0 - c.angular_frequency_rad_s * time_s + c.phase_rad);
    const std::complex<double> rotation = std::polar(1.0, c.tangential_wavenumber_rad_m * tangential_spacing_m_);
    for (int j = span_begin_; j < span_end_; ++j) {
      line_[static_cast<std::size_t>(j)] += z.real();
      z *= rotation;
    }
  }
  const double scale = r * dt;
  for (int i = strip_begin_; i < strip_end_; ++i) {
    const double p = scale * profile_[static_cast<std::size_t>(i - strip_begin_)];
    for (int j = span_begin_; j < span_end_; ++j) {
      const std::size_t cell = normal_is_x_ ? static_cast<std::size_t>(j) * y_stride + static_cast<std::size_t>(i) * x_stride
                                            : static_cast<std::size_t>(i) * y_stride + static_cast<std::size_t>(j) * x_stride;
      if (water_[static_cast<std::size_t>(i - strip_begin_) * tangential_count + j])
        eta_base[cell] += p * line_[static_cast<std::size_t>(j)];
    }
  }
}

}  // namespace nearshore::boussinesq::detail
