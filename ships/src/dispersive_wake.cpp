#include "nearshore/ships/dispersive_wake.hpp"

#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <type_traits>

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

bool thin_ship_options_ok(const DispersiveWakeOptions& o) {
  return o.source_layers >= 2 && o.source_layers <= 32 && o.breaking_slope >= 0.0 && o.breaking_slope <= 10.0;
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

// The thin-ship sources' scratch and their spectrum: M = N / 2 nodes a side at twice the layer's
// spacing (the band the forcing's smoothing leaves), one splat per depth level.
struct DispersiveWake::Sources {
  explicit Sources(int n_full, int levels)
      : m(n_full / 2), modes(static_cast<std::size_t>(m) * (m / 2 + 1)), levels(levels),
        splat(static_cast<std::size_t>(levels) * m * m, 0.0f), spectrum(modes, {0.0, 0.0}),
        level_spectra(2 * modes * levels, 0.0f) {
    real = fftwf_alloc_real(static_cast<std::size_t>(m) * m);
    out = fftwf_alloc_complex(modes);
    forward = fftwf_plan_dft_r2c_2d(m, m, real, out, FFTW_ESTIMATE);
    if (!real || !out || !forward)
      throw Error("DispersiveWake", fmt::format("FFTW could not plan a {} x {} float transform", m, m),
                  "use fewer cells (memory) or check the FFTW installation");
  }
  ~Sources() {
    if (forward) fftwf_destroy_plan(forward);
    fftwf_free(real);
    fftwf_free(out);
  }
  int m;
  std::size_t modes;
  int levels;
  std::vector<float> splat;                       ///< levels x m x m source amounts (m^3/s)
  std::vector<std::complex<double>> spectrum;     ///< A(k), smoothed, on the m x (m/2 + 1) band
  std::vector<float> level_spectra;               ///< each level's transform (re, im per mode)
  std::vector<double> wavenumber;                 ///< |k| per mode of the band
  float* real = nullptr;
  fftwf_complex* out = nullptr;
  fftwf_plan forward = nullptr;
  bool valid = false;   ///< spectrum holds the last forcing's sources
  double depth_m = 0.0;
};

namespace {

// Fraction of a triangle where a linear function with corner values f0, f1, f2 is positive (the
// wet part of a piece, f the depth below the surface): exact for a linear f.
double positive_fraction(double f0, double f1, double f2) {
  const int wet = (f0 > 0) + (f1 > 0) + (f2 > 0);
  if (wet == 3) return 1.0;
  if (wet == 0) return 0.0;
  // The lone corner on one side, a, and the two others b, c: the sub-triangle at a has the area
  // fraction a^2 / ((a - b)(a - c)).
  auto lone = [](double a, double b, double c) { return a * a / ((a - b) * (a - c)); };
  if (wet == 1) {
    if (f0 > 0) return lone(f0, f1, f2);
    if (f1 > 0) return lone(f1, f0, f2);
    return lone(f2, f0, f1);
  }
  if (f0 <= 0) return 1.0 - lone(f0, f1, f2);
  if (f1 <= 0) return 1.0 - lone(f1, f0, f2);
  return 1.0 - lone(f2, f0, f1);
}

}  // namespace

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
  if (!(thin_ship_options_ok(options_)))
    throw Error("DispersiveWakeOptions",
                fmt::format("source_layers = {}, breaking_slope = {}", options_.source_layers, options_.breaking_slope),
                "use 2 to 32 depth levels for the thin-ship sources and a breaking slope of 0 (off) to 10");
  spectral_ = std::make_unique<Spectral>(n_);
  sources_ = std::make_unique<Sources>(n_, options_.source_layers);
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
  // Node (i, j) now holds what node (i + di, j + dj) held; nodes that enter hold `entering` (rest,
  // or a solid mask's "not looked up yet").
  auto shift = [&](auto& a, auto entering) {
    std::remove_reference_t<decltype(a)> out(a.size(), entering);
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
  shift(eta_, 0.0f);
  shift(phi_, 0.0f);
  if (solids_of_ != nullptr) shift(solid_, kUnknown);
}

void DispersiveWake::set_solids(const HarbourObstacles* obstacles, double hull_x_m, double hull_y_m) {
  if (obstacles == nullptr || !obstacles->any()) {
    solids_of_ = nullptr;
    held_.clear();
    any_solid_ = false;
    return;
  }
  if (obstacles != solids_of_ || solid_.size() != eta_.size()) {
    solid_.assign(eta_.size(), kUnknown);
    held_.clear();
    solids_of_ = obstacles;
  }
  // The reach only changes when the window has moved (the hull keeps its node in the window).
  if (origin_i_ == reach_origin_i_ && origin_j_ == reach_origin_j_ && held_.size() == solid_.size()) return;
  reach_origin_i_ = origin_i_;
  reach_origin_j_ = origin_j_;
  bool any = false;
  for (int j = 0; j < n_; ++j)
    for (int i = 0; i < n_; ++i) {
      unsigned char& s = solid_[index(i, j)];
      if (s == kUnknown) {
        const double x = static_cast<double>(origin_i_ + i) * spacing_m_, y = static_cast<double>(origin_j_ + j) * spacing_m_;
        s = obstacles->signed_distance_m(x, y) < 0.0 ? kSolid : kWater;
      }
      any = any || s == kSolid;
    }
  any_solid_ = any;
  if (!any) return;
  // The hull's reach: a flood fill over water nodes from the hull's node (4-connected, no wrap).
  held_.assign(solid_.size(), 1);
  const long long hi = std::llround(hull_x_m / spacing_m_) - origin_i_, hj = std::llround(hull_y_m / spacing_m_) - origin_j_;
  if (hi < 0 || hj < 0 || hi >= n_ || hj >= n_ || solid_[index(static_cast<int>(hi), static_cast<int>(hj))] != kWater) {
    for (std::size_t k = 0; k < held_.size(); ++k) held_[k] = solid_[k] == kSolid ? 1 : 0;  // no reach to follow
    return;
  }
  std::vector<int>& stack = fill_scratch_;
  stack.clear();
  auto visit = [&](int i, int j) {
    const std::size_t k = index(i, j);
    if (held_[k] == 1 && solid_[k] == kWater) {
      held_[k] = 0;
      stack.push_back(static_cast<int>(k));
    }
  };
  visit(static_cast<int>(hi), static_cast<int>(hj));
  while (!stack.empty()) {
    const int k = stack.back();
    stack.pop_back();
    const int i = k % n_, j = k / n_;
    if (i > 0) visit(i - 1, j);
    if (i + 1 < n_) visit(i + 1, j);
    if (j > 0) visit(i, j - 1);
    if (j + 1 < n_) visit(i, j + 1);
  }
}

void DispersiveWake::cut_off_forcing() {
  if (!any_solid_) return;
  for (std::size_t k = 0; k < zeta_.size(); ++k)
    if (held_[k] != 0) zeta_[k] = 0.0f;
}

void DispersiveWake::hold_solids_at_rest() {
  if (!any_solid_) return;
  for (std::size_t k = 0; k < eta_.size(); ++k)
    if (held_[k] != 0) {
      eta_[k] = -zeta_[k];
      phi_[k] = 0.0f;
    }
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
  hold_solids_at_rest();
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
  breaking_.clear();
  for (int s = 0; s < steps; ++s) {
    step();
    break_steep_crests(s + 1 == steps ? &breaking_ : nullptr);
  }
  refresh_heights();
}

void DispersiveWake::break_steep_crests(std::vector<BreakingNode>* record) {
  const double limit = options_.breaking_slope;
  if (!(limit > 0.0)) return;
  // Central differences see 90 % of the slope of an 8-node wave (sin(k dx) / (k dx)), the shortest
  // the forcing's smoothing leaves with much energy; the limit is applied to what they see.
  const double inv_2dx = 0.5 / spacing_m_, limit2 = limit * limit;
  const bool patch = options_.forcing == DispersiveWakeOptions::HullForcing::pressure_patch;
  // The slopes first (the scaling must not feed its neighbours' slopes in the same pass).
  std::vector<std::pair<std::size_t, float>>& scale = break_scratch_;
  scale.clear();
  for (int j = 1; j + 1 < n_; ++j)
    for (int i = 1; i + 1 < n_; ++i) {
      const std::size_t c = index(i, j);
      // Under a pressure-patch hull the depression's sides are the hull, not a wave.
      if (patch && zeta_[c] > 1e-3f) continue;
      const double sx = (eta_[c + 1] - eta_[c - 1]) * inv_2dx;
      const double sy = (eta_[c + n_] - eta_[c - n_]) * inv_2dx;
      const double s2 = sx * sx + sy * sy;
      if (s2 > limit2) scale.emplace_back(c, static_cast<float>(limit / std::sqrt(s2)));
    }
  for (const auto& [c, r] : scale) {
    eta_[c] = -zeta_[c] + r * (eta_[c] + zeta_[c]);
    phi_[c] *= r;
  }
  if (record == nullptr) return;
  // At most one node per 2 x 2 block: the largest excess there.
  for (const auto& [c, r] : scale) {
    const int i = static_cast<int>(c % n_), j = static_cast<int>(c / n_);
    const double x = (static_cast<double>(origin_i_) + i) * spacing_m_, y = (static_cast<double>(origin_j_) + j) * spacing_m_;
    const double excess = 1.0 / r - 1.0;
    if (!record->empty()) {
      BreakingNode& last = record->back();
      if (std::abs(last.x_m - x) < 1.5 * spacing_m_ && std::abs(last.y_m - y) < 1.5 * spacing_m_) {
        if (excess > last.excess) last = {x, y, excess};
        continue;
      }
    }
    record->push_back({x, y, excess});
  }
}

void DispersiveWake::force_with_thin_ship(const ShipBody& body, double depth_m) {
  Sources& src = *sources_;
  const int m = src.m, levels = src.levels;
  const double depth = std::clamp(depth_m, 1e-3, options_.max_depth_m);
  const double coarse = 2.0 * spacing_m_;
  const HullSamples& samples = body.samples();
  const std::vector<double>& eta = body.water_elevations_m();
  const ShipState& state = body.state();
  const Eigen::Matrix3d rotation = state.orientation.toRotationMatrix();
  const Eigen::Vector2d velocity = state.velocity_m_s.head<2>();
  // 1. Each wet piece's source: m = (v . n) A (wet fraction), at its depth below the local surface,
  //    on the body's centreplane (Michell). The deepest source sets the depth levels.
  std::vector<SourcePoint>& sources = source_scratch_;
  sources.clear();
  double deepest = 0.0;
  for (std::size_t p = 0; p < samples.size(); ++p) {
    const double surface = p < eta.size() ? eta[p] : 0.0;
    const auto& corners = samples.corner_m[p];
    const double wet = positive_fraction(surface - body.to_world(corners[0]).z(), surface - body.to_world(corners[1]).z(),
                                         surface - body.to_world(corners[2]).z());
    if (wet <= 0.0) continue;
    const Eigen::Vector3d point = body.to_world(samples.position_m[p]);
    const Eigen::Vector3d arm = point - state.position_m;
    const Eigen::Vector3d point_velocity = state.velocity_m_s + state.angular_velocity_rad_s.cross(arm);
    const double strength = point_velocity.dot(rotation * samples.normal[p]) * samples.area_m2[p] * wet;
    Eigen::Vector3d on_centreplane = samples.position_m[p];
    on_centreplane.y() = 0.0;
    const Eigen::Vector3d centre = body.to_world(on_centreplane);
    const double below = std::clamp(surface - point.z(), 0.0, depth);
    deepest = std::max(deepest, below);
    sources.push_back({centre.x(), centre.y(), below, strength});
  }
  // 2. Splat on the coarse grid's levels: bilinear across, linear in depth between levels.
  const double dz = std::max(deepest, 1e-3) / (levels - 1);
  std::fill(src.splat.begin(), src.splat.end(), 0.0f);
  const double x0 = static_cast<double>(origin_i_) * spacing_m_, y0 = static_cast<double>(origin_j_) * spacing_m_;
  const std::size_t plane = static_cast<std::size_t>(m) * m;
  for (const SourcePoint& q : sources) {
    const double u = (q.x - x0) / coarse, v = (q.y - y0) / coarse;
    const int i0 = static_cast<int>(std::floor(u)), j0 = static_cast<int>(std::floor(v));
    if (i0 < 0 || j0 < 0 || i0 + 1 >= m || j0 + 1 >= m) continue;
    const double a = u - i0, b = v - j0;
    const double level = std::min(q.depth / dz, levels - 1.0);
    const int l0 = std::min(static_cast<int>(level), levels - 2);
    const double c = level - l0;
    for (int l = 0; l < 2; ++l) {
      const double w = (l == 0 ? 1.0 - c : c) * q.strength;
      float* s = src.splat.data() + static_cast<std::size_t>(l0 + l) * plane;
      s[static_cast<std::size_t>(j0) * m + i0] += static_cast<float>((1 - a) * (1 - b) * w);
      s[static_cast<std::size_t>(j0) * m + i0 + 1] += static_cast<float>(a * (1 - b) * w);
      s[static_cast<std::size_t>(j0 + 1) * m + i0] += static_cast<float>((1 - a) * b * w);
      s[static_cast<std::size_t>(j0 + 1) * m + i0 + 1] += static_cast<float>(a * b * w);
    }
  }
  // 3. A(k) = sum over levels of cosh(k (d - z_l)) / cosh(k d) times the level's transform, smoothed
  //    as the patch's binomial passes smooth (cos^(2P)(k dx / 2) in x and y).
  const int half = m / 2 + 1;
  const double dk = 2.0 * std::numbers::pi / (n_ * spacing_m_);
  if (src.wavenumber.empty()) {
    src.wavenumber.resize(src.modes);
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < half; ++i)
        src.wavenumber[static_cast<std::size_t>(j) * half + i] = std::hypot(dk * i, dk * (j <= m / 2 ? j : j - m));
  }
  for (int l = 0; l < levels; ++l) {
    std::copy_n(src.splat.data() + static_cast<std::size_t>(l) * plane, plane, src.real);
    fftwf_execute(src.forward);
    std::copy_n(&src.out[0][0], 2 * src.modes, src.level_spectra.data() + 2 * src.modes * l);
  }
  // Per mode, e^{-k z_l} = r^l with r = e^{-k dz}; the bed's image e^{-k (2 d - z_l)} = e^{-2 k d} / r^l.
  const int passes = options_.source_smoothing_passes;
  for (std::size_t k = 0; k < src.modes; ++k) {
    const double kk = src.wavenumber[k];
    const double r = std::exp(-kk * dz), bed = std::exp(-2.0 * kk * depth), norm = 1.0 / (1.0 + bed);
    // The bed's image matters only where e^{-2 k d} does (shallow water, long waves).
    const double up_step = bed > 1e-12 ? std::exp(kk * dz) : 0.0;
    double down = norm, up = bed * norm;  // e^{-k z_l} and e^{-2 k d} e^{k z_l}, over 1 + e^{-2 k d}
    double re = 0.0, im = 0.0;
    for (int l = 0; l < levels; ++l) {
      const float* c = src.level_spectra.data() + 2 * (src.modes * l + k);
      const double w = down + up;
      re += w * c[0];
      im += w * c[1];
      down *= r;
      up *= up_step;
    }
    std::complex<double> a(re, im);
    if (passes > 0) {
      const int i = static_cast<int>(k % half), j = static_cast<int>(k / half);
      const double cx = std::cos(0.5 * dk * i * spacing_m_), cy = std::cos(0.5 * dk * (j <= m / 2 ? j : j - m) * spacing_m_);
      a *= std::pow(cx * cx * cy * cy, passes);
    }
    src.spectrum[k] = a;
  }
  src.valid = true;
  src.depth_m = depth;
  // 4. zeta^(k) = i (k . V) A(k) / (g k tanh(k d)) on the band, 0 above it; to space.
  Spectral& f = *spectral_;
  const int full_half = n_ / 2 + 1;
  std::fill(&f.eta_hat[0][0], &f.eta_hat[0][0] + 2 * f.modes, 0.0f);
  for (int j = 0; j < m; ++j) {
    const int jj = j <= m / 2 ? j : j - m;
    if (jj == -m / 2 || jj == m / 2) continue;  // the coarse grid's Nyquist: not a resolved wave
    const int jf = jj >= 0 ? jj : jj + n_;
    for (int i = 0; i < m / 2; ++i) {
      const double kx = dk * i, ky = dk * jj, kk = std::hypot(kx, ky);
      if (kk == 0.0) continue;  // the sources sum to no volume; the mean head is 0
      const std::complex<double> a = src.spectrum[static_cast<std::size_t>(j) * half + i];
      const std::complex<double> head =
          std::complex<double>(0.0, kx * velocity.x() + ky * velocity.y()) * a / (kGravity * kk * std::tanh(kk * depth));
      float* out = f.eta_hat[static_cast<std::size_t>(jf) * full_half + i];
      out[0] = static_cast<float>(head.real());
      out[1] = static_cast<float>(head.imag());
    }
  }
  fftwf_execute(f.inverse_eta);
  const double area = std::pow(n_ * spacing_m_, 2);
  for (std::size_t k = 0; k < zeta_.size(); ++k) zeta_[k] = static_cast<float>(f.real[k] / area);
}

Eigen::Vector2d DispersiveWake::wave_force_N(double density_kg_m3) const {
  const Sources& src = *sources_;
  if (!src.valid) return Eigen::Vector2d::Zero();
  // sum_p m_p grad phi_w(x_p, z_p) = (1 / N^2) sum_k i k Phi(k) conj(A(k)), Phi = FFT(phi) (FFTW's
  // unnormalised transform), phi_w continued down by cosh(k (d - z)) / cosh(k d) as A(k) holds it.
  Spectral& f = *spectral_;
  std::copy(phi_.begin(), phi_.end(), f.real);
  fftwf_execute(f.forward_phi);
  const int m = src.m, half = m / 2 + 1, full_half = n_ / 2 + 1;
  const double dk = 2.0 * std::numbers::pi / (n_ * spacing_m_);
  std::complex<double> sx(0.0, 0.0), sy(0.0, 0.0);
  for (int j = 0; j < m; ++j) {
    const int jj = j <= m / 2 ? j : j - m;
    if (jj == -m / 2 || jj == m / 2) continue;
    const int jf = jj >= 0 ? jj : jj + n_;
    for (int i = 0; i < m / 2; ++i) {
      const std::complex<double> phi(f.phi_hat[static_cast<std::size_t>(jf) * full_half + i][0],
                                     f.phi_hat[static_cast<std::size_t>(jf) * full_half + i][1]);
      const std::complex<double> term = phi * std::conj(src.spectrum[static_cast<std::size_t>(j) * half + i]);
      const double twice = i == 0 ? 1.0 : 2.0;  // the half spectrum's mirror modes
      sx += twice * std::complex<double>(0.0, dk * i) * term;
      sy += twice * std::complex<double>(0.0, dk * jj) * term;
    }
  }
  const double scale = -density_kg_m3 / (static_cast<double>(n_) * n_);
  return {scale * sx.real(), scale * sy.real()};
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
  if (!started_) solids_of_ = nullptr;  // a restart looks every node up again
  set_solids(seabed != nullptr ? seabed->obstacles() : nullptr, centre.x(), centre.y());
  // 2. The forcing: the hull's pressure head on the nodes (the corners of hull_pressure_head; the
  //    last row and column fall in the absorbing layer's far side and are dropped).
  //    With the thin ship: the sources' head over the depth under the hull.
  const double depth = seabed != nullptr ? seabed->depth_m(centre.x(), centre.y()) : options_.max_depth_m;
  if (options_.forcing == DispersiveWakeOptions::HullForcing::thin_ship) {
    force_with_thin_ship(body, depth);
  } else {
    hull_pressure_head(body, origin_i_, origin_j_, spacing_m_, n_, options_.smoothing_passes, head_);
    for (int j = 0; j < n_; ++j)
      for (int i = 0; i < n_; ++i)
        zeta_[index(i, j)] = static_cast<float>(head_[static_cast<std::size_t>(j) * (n_ + 1) + i]);
  }
  cut_off_forcing();
  if (!started_) {
    rest_in_depression();
    started_ = true;
  }
  // 3. Advance over the depth under the hull.
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
