#include "nearshore/ships/dispersive_wake.hpp"

#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>

#include <fmt/format.h>

#include "nearshore/core/error.hpp"

namespace nearshore::ships {
namespace {

constexpr double kGravity = 9.81;  // m/s^2, as WaterProperties

void check_options(const DispersiveWakeOptions& o, double spacing_m) {
  if (o.cells < 32 || o.cells % 2 != 0 || !(spacing_m > 0.0) || !(o.max_depth_m > 0.0) ||
      !(o.absorbing_fraction >= 0.0 && o.absorbing_fraction < 0.5) || !(o.max_step_s > 0.0) ||
      !(std::abs(o.astern_fraction) < 0.5))
    throw Error("DispersiveWakeOptions",
                fmt::format("cells = {}, spacing = {} m, max_depth_m = {}, absorbing_fraction = {}, max_step_s = {}, "
                            "astern_fraction = {}",
                            o.cells, spacing_m, o.max_depth_m, o.absorbing_fraction, o.max_step_s, o.astern_fraction),
                "use an even number of at least 32 cells, a positive spacing, depth and step, an absorbing layer "
                "under half the side and the window's centre within it (|astern_fraction| < 0.5)");
}

}  // namespace

// FFTW's float plans and their buffers (fftwf_malloc: aligned for its SIMD kernels). The plans are
// made once (FFTW_MEASURE would time candidate algorithms at every construction and make the
// results depend on the machine's load; FFTW_ESTIMATE picks deterministically).
struct DispersiveWake::Spectral {
  explicit Spectral(int n) : n(n), modes(static_cast<std::size_t>(n) * (n / 2 + 1)) {
    real = fftwf_alloc_real(static_cast<std::size_t>(n) * n);
    eta_hat = fftwf_alloc_complex(modes);
    phi_hat = fftwf_alloc_complex(modes);
    forward_eta = fftwf_plan_dft_r2c_2d(n, n, real, eta_hat, FFTW_ESTIMATE);
    forward_phi = fftwf_plan_dft_r2c_2d(n, n, real, phi_hat, FFTW_ESTIMATE);
    inverse_eta = fftwf_plan_dft_c2r_2d(n, n, eta_hat, real, FFTW_ESTIMATE);
    inverse_phi = fftwf_plan_dft_c2r_2d(n, n, phi_hat, real, FFTW_ESTIMATE);
    if (!real || !eta_hat || !phi_hat || !forward_eta || !forward_phi || !inverse_eta || !inverse_phi)
      throw Error("DispersiveWake", fmt::format("FFTW could not plan a {} x {} float transform", n, n),
                  "use fewer cells (memory) or check the FFTW installation");
  }
  ~Spectral() {
    for (fftwf_plan p : {forward_eta, forward_phi, inverse_eta, inverse_phi})
      if (p) fftwf_destroy_plan(p);
    fftwf_free(real);
    fftwf_free(eta_hat);
    fftwf_free(phi_hat);
  }
  int n;
  std::size_t modes;
  float* real = nullptr;
  fftwf_complex* eta_hat = nullptr;
  fftwf_complex* phi_hat = nullptr;
  fftwf_plan forward_eta = nullptr, forward_phi = nullptr, inverse_eta = nullptr, inverse_phi = nullptr;
};

DispersiveWake::DispersiveWake(const ShipParticulars& particulars, DispersiveWakeOptions options)
    : DispersiveWake(options.side_in_lengths * std::max(particulars.length_m, 1e-3) / std::max(options.cells, 2),
                     options) {
  if (!(options.side_in_lengths > 1.0))
    throw Error("DispersiveWakeOptions", fmt::format("side_in_lengths = {}", options.side_in_lengths),
                "use a window longer than the ship (side_in_lengths > 1)");
}

DispersiveWake::DispersiveWake(double spacing_m, DispersiveWakeOptions options)
    : options_(options), n_(options.cells), spacing_m_(spacing_m), depth_m_(options.max_depth_m) {
  check_options(options_, spacing_m_);
  spectral_ = std::make_unique<Spectral>(n_);
  const std::size_t nodes = static_cast<std::size_t>(n_) * n_;
  eta_.assign(nodes, 0.0f);
  phi_.assign(nodes, 0.0f);
  zeta_.assign(nodes, 0.0f);
  heights_m_.assign(nodes, 0.0f);
}

DispersiveWake::~DispersiveWake() = default;

void DispersiveWake::move_window(long long origin_i, long long origin_j) {
  const long long di = origin_i - origin_i_, dj = origin_j - origin_j_;
  origin_i_ = origin_i;
  origin_j_ = origin_j;
  if (di == 0 && dj == 0) return;
  // Node (i, j) now holds what node (i + di, j + dj) held; nodes that enter are at rest.
  auto shift = [&](std::vector<float>& a) {
    std::vector<float> out(a.size(), 0.0f);
    for (int j = 0; j < n_; ++j) {
      const long long sj = j + dj;
      if (sj < 0 || sj >= n_) continue;
      for (int i = 0; i < n_; ++i) {
        const long long si = i + di;
        if (si >= 0 && si < n_) out[index(i, j)] = a[index(static_cast<int>(si), static_cast<int>(sj))];
      }
    }
    a.swap(out);
  };
  shift(eta_);
  shift(phi_);
}

void DispersiveWake::rest_in_depression() {
  for (std::size_t k = 0; k < eta_.size(); ++k) {
    eta_[k] = -zeta_[k];
    phi_[k] = 0.0f;
  }
}

void DispersiveWake::prepare_rotation(double dt_s, double depth_m) {
  // Recomputed only when the step or the depth changes by more than 0.1 % (the depth under a ship
  // varies slowly; a 0.1 % change in d moves omega by less than 0.05 %).
  if (rotation_dt_s_ == dt_s && std::abs(depth_m - rotation_depth_m_) <= 1e-3 * rotation_depth_m_) return;
  rotation_dt_s_ = dt_s;
  rotation_depth_m_ = depth_m;
  const int half = n_ / 2 + 1;
  const std::size_t modes = static_cast<std::size_t>(n_) * half;
  cos_.resize(modes);
  eta_from_phi_.resize(modes);
  phi_from_eta_.resize(modes);
  const double dk = 2.0 * std::numbers::pi / (n_ * spacing_m_);
  const double inv_nodes = 1.0 / (static_cast<double>(n_) * n_);  // FFTW's transforms are unnormalised
  for (int j = 0; j < n_; ++j) {
    const double ky = dk * (j <= n_ / 2 ? j : j - n_);
    for (int i = 0; i < half; ++i) {
      const double kx = dk * i, k = std::hypot(kx, ky);
      const std::size_t m = static_cast<std::size_t>(j) * half + i;
      if (k == 0.0) {
        // The mean elevation is the volume and stays; the mean potential carries no velocity.
        cos_[m] = static_cast<float>(inv_nodes);
        eta_from_phi_[m] = 0.0f;
        phi_from_eta_[m] = 0.0f;
        continue;
      }
      const double t = k * std::tanh(k * depth_m);  // eta_t = t phi
      const double omega = std::sqrt(kGravity * t);  // linear dispersion relation, finite depth
      const double c = std::cos(omega * dt_s), s = std::sin(omega * dt_s);
      cos_[m] = static_cast<float>(c * inv_nodes);
      eta_from_phi_[m] = static_cast<float>(t / omega * s * inv_nodes);
      phi_from_eta_[m] = static_cast<float>(-kGravity / omega * s * inv_nodes);
    }
  }
  // The absorbing layer's factor per node for this step: exp(-rate r^2 dt), r the depth into the
  // layer over its width (as BowWave::absorb; the seed's radial fade, eq. 4.16, as a sponge).
  keep_.assign(static_cast<std::size_t>(n_) * n_, 1.0f);
  const double width = options_.absorbing_fraction * n_;
  if (width > 0.0)
    for (int j = 0; j < n_; ++j)
      for (int i = 0; i < n_; ++i) {
        const double inside = std::min({i + 0.5, n_ - i - 0.5, j + 0.5, n_ - j - 0.5});
        if (inside >= width) continue;
        const double r = (width - inside) / width;
        keep_[index(i, j)] = static_cast<float>(std::exp(-options_.absorbing_rate_per_s * r * r * dt_s));
      }
}

void DispersiveWake::step() {
  Spectral& f = *spectral_;
  const std::size_t nodes = eta_.size();
  // 1. e = eta + zeta and phi to Fourier space.
  for (std::size_t k = 0; k < nodes; ++k) f.real[k] = eta_[k] + zeta_[k];
  fftwf_execute(f.forward_eta);
  std::copy(phi_.begin(), phi_.end(), f.real);
  fftwf_execute(f.forward_phi);
  // 2. The exact rotation of every mode (header), normalisation folded in.
  for (std::size_t m = 0; m < f.modes; ++m) {
    const float c = cos_[m], a = eta_from_phi_[m], b = phi_from_eta_[m];
    const float er = f.eta_hat[m][0], ei = f.eta_hat[m][1], pr = f.phi_hat[m][0], pi = f.phi_hat[m][1];
    f.eta_hat[m][0] = c * er + a * pr;
    f.eta_hat[m][1] = c * ei + a * pi;
    f.phi_hat[m][0] = c * pr + b * er;
    f.phi_hat[m][1] = c * pi + b * ei;
  }
  f.phi_hat[0][0] = f.phi_hat[0][1] = 0.0f;
  // 3. Back to space: eta = e - zeta.
  fftwf_execute(f.inverse_eta);
  for (std::size_t k = 0; k < nodes; ++k) eta_[k] = f.real[k] - zeta_[k];
  fftwf_execute(f.inverse_phi);
  std::copy(f.real, f.real + nodes, phi_.begin());
  absorb();
}

void DispersiveWake::absorb() {
  if (options_.absorbing_fraction <= 0.0) return;
  // Relax toward rest: eta -> -zeta (zeta is 0 in the layer unless a hull reaches it), phi -> 0.
  for (std::size_t k = 0; k < eta_.size(); ++k) {
    const float keep = keep_[k];
    eta_[k] = -zeta_[k] + keep * (eta_[k] + zeta_[k]);
    phi_[k] *= keep;
  }
}

void DispersiveWake::advance(double dt_s, double depth_m) {
  if (!(dt_s > 0.0)) return;
  depth_m_ = std::clamp(depth_m, 1e-3, options_.max_depth_m);
  const int steps = std::max(1, static_cast<int>(std::ceil(dt_s / options_.max_step_s - 1e-9)));
  prepare_rotation(dt_s / steps, depth_m_);
  for (int s = 0; s < steps; ++s) step();
  refresh_heights();
}

void DispersiveWake::update(const ShipBody& body, const Seabed* seabed, double dt_s) {
  // 1. The window: its centre astern_fraction of the side behind the hull's centre.
  const Eigen::Vector3d centre = body.to_world(body.particulars().hull_centre_m);
  const Eigen::Vector3d forward = body.state().orientation * Eigen::Vector3d::UnitX();
  Eigen::Vector2d ahead(forward.x(), forward.y());
  ahead = ahead.norm() > 1e-9 ? Eigen::Vector2d(ahead.normalized()) : Eigen::Vector2d::UnitX();
  const double side = n_ * spacing_m_;
  const Eigen::Vector2d window_centre = centre.head<2>() - options_.astern_fraction * side * ahead;
  const long long want_i = std::llround(window_centre.x() / spacing_m_) - n_ / 2;
  const long long want_j = std::llround(window_centre.y() / spacing_m_) - n_ / 2;
  if (!started_) {
    std::fill(eta_.begin(), eta_.end(), 0.0f);
    std::fill(phi_.begin(), phi_.end(), 0.0f);
    origin_i_ = want_i;
    origin_j_ = want_j;
  } else {
    move_window(want_i, want_j);
  }
  // 2. The forcing: the hull's pressure head on the nodes (the corners of hull_pressure_head; the
  //    last row and column fall in the absorbing layer's far side and are dropped).
  hull_pressure_head(body, origin_i_, origin_j_, spacing_m_, n_, options_.smoothing_passes, head_);
  for (int j = 0; j < n_; ++j)
    for (int i = 0; i < n_; ++i)
      zeta_[index(i, j)] = static_cast<float>(head_[static_cast<std::size_t>(j) * (n_ + 1) + i]);
  if (!started_) {
    rest_in_depression();
    started_ = true;
  }
  // 3. The depth under the hull.
  const double depth = seabed != nullptr ? seabed->depth_m(centre.x(), centre.y()) : options_.max_depth_m;
  advance(dt_s, depth);
  if (!(dt_s > 0.0)) refresh_heights();
}

void DispersiveWake::refresh_heights() {
  for (std::size_t k = 0; k < eta_.size(); ++k) heights_m_[k] = static_cast<float>(shown_weight_ * eta_[k]);
  ++serial_;
}

void DispersiveWake::set_shown_weight(double weight) {
  weight = std::clamp(weight, 0.0, 1.0);
  if (weight == shown_weight_) return;
  shown_weight_ = weight;
  refresh_heights();
}

BowWaveField DispersiveWake::field() const {
  BowWaveField f;
  // Cell (i, j) of the field is centred on node (i, j).
  f.origin_x_m = (static_cast<double>(origin_i_) - 0.5) * spacing_m_;
  f.origin_y_m = (static_cast<double>(origin_j_) - 0.5) * spacing_m_;
  f.spacing_m = spacing_m_;
  f.columns = f.rows = n_;
  f.heights_m = &heights_m_;
  f.serial = serial_;
  return f;
}

double DispersiveWake::elevation_m(double x_m, double y_m) const {
  return field_elevation_m(field(), x_m, y_m);
}

WakeAngle measure_wake_envelope_angle(const DispersiveWake& wake, const ShipState& state, double length_m,
                                      double start_lengths, double min_lateral_m) {
  return measure_wake_envelope_angle(wake.field(), wake.options().absorbing_fraction, state, length_m, start_lengths,
                                     min_lateral_m);
}

}  // namespace nearshore::ships
