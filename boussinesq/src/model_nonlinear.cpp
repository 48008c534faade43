// Weakly nonlinear properties of the continuous equations (model_nonlinear.hpp); the derivation of
// the second-order transfer function is in docs/validation.md ("Nonlinear checks").
#include "nearshore/boussinesq/model_nonlinear.hpp"

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <mutex>
#include <numbers>
#include <utility>
#include <vector>

#include <Eigen/Dense>
#include <fmt/format.h>

#include "nearshore/core/error.hpp"
#include "nearshore/ocean/linear_waves.hpp"

namespace nearshore::boussinesq {
namespace {

constexpr double g = ocean::kGravity_m_s2;

// Linear phase speed squared of the equations: c0^2 = g d (1 + B (kd)^2) / (1 + (B+1/3) (kd)^2).
double linear_phase_speed_squared(double k, double d, double B) {
  const double kd2 = k * d * k * d;
  return g * d * (1.0 + B * kd2) / (1.0 + (B + 1.0 / 3.0) * kd2);
}

// cos and sin of 2 pi q / M, q = 0..M-1: every product m theta_j of the quadrature is one of these
// (cos(m theta_j) = cos(2 pi ((m j) mod M) / M)), made once per steady wave, not once per derivative.
struct QuadratureAngles {
  explicit QuadratureAngles(int M) : cos_q(M), sin_q(M) {
    for (int q = 0; q < M; ++q) {
      cos_q[q] = std::cos(2.0 * std::numbers::pi * q / M);
      sin_q[q] = std::sin(2.0 * std::numbers::pi * q / M);
    }
  }
  std::vector<double> cos_q, sin_q;
};

// d^order/dtheta^order of a 2 pi-periodic function given by its samples at theta_j = 2 pi j / M, by
// the discrete Fourier series (exact for trigonometric polynomials of degree < M/2; the quadrature
// of boussinesq_steady_wave has 8 points per retained harmonic, so the products stay resolved).
std::vector<double> periodic_derivative(const std::vector<double>& samples, int order, const QuadratureAngles& angles) {
  const int M = static_cast<int>(samples.size());
  const std::vector<double>&cos_q = angles.cos_q, &sin_q = angles.sin_q;
  std::vector<double> out(M, 0.0);
  for (int m = 1; m < M / 2; ++m) {
    double a = 0.0, b = 0.0;  // samples ~ a cos(m theta) + b sin(m theta)
    // q = (m j) mod M, stepped by m (0 < m < M): no integer division in the loop.
    for (int j = 0, q = 0; j < M; ++j, q = q + m >= M ? q + m - M : q + m) {
      a += 2.0 / M * samples[j] * cos_q[q];
      b += 2.0 / M * samples[j] * sin_q[q];
    }
    // d/dtheta maps (a, b) -> m (b, -a); `order` times.
    for (int o = 0; o < order; ++o) {
      const double a_next = m * b, b_next = -m * a;
      a = a_next;
      b = b_next;
    }
    for (int j = 0, q = 0; j < M; ++j, q = q + m >= M ? q + m - M : q + m) out[j] += a * cos_q[q] + b * sin_q[q];
  }
  return out;
}

// The momentum residual of Equations::kFullyNonlinear for a steady wave eta(theta), P = c eta,
// theta = k x - w t (so d/dx = k d/dtheta, d/dt = -c k d/dtheta), at the M quadrature points.
std::vector<double> fully_nonlinear_residual(const std::vector<double>& eta, double c, double k, double d, double B,
                                             const QuadratureAngles& angles) {
  const std::size_t M = eta.size();
  auto dx = [&](const std::vector<double>& f) {
    std::vector<double> out = periodic_derivative(f, 1, angles);
    for (double& v : out) v *= k;
    return out;
  };
  auto dt = [&](const std::vector<double>& f) {
    std::vector<double> out = dx(f);
    for (double& v : out) v *= -c;
    return out;
  };
  std::vector<double> h(M), P(M), u(M), flux(M), h3_gamma(M);
  for (std::size_t j = 0; j < M; ++j) {
    h[j] = d + eta[j];
    P[j] = c * eta[j];
    u[j] = P[j] / h[j];
    flux[j] = P[j] * P[j] / h[j];
  }
  const std::vector<double> P_t = dt(P), flux_x = dx(flux), eta_x = dx(eta), u_x = dx(u), u_xx = dx(u_x),
                            u_xt = dx(dt(u));
  std::vector<double> S(M);  // the shallow-water momentum residual
  for (std::size_t j = 0; j < M; ++j) {
    S[j] = P_t[j] + flux_x[j] + g * h[j] * eta_x[j];
    h3_gamma[j] = h[j] * h[j] * h[j] * (u_xt[j] + u[j] * u_xx[j] - u_x[j] * u_x[j]);
  }
  const std::vector<double> serre = dx(h3_gamma), S_xx = dx(dx(S));
  std::vector<double> r(M);
  for (std::size_t j = 0; j < M; ++j) r[j] = S[j] - serre[j] / 3.0 - B * h[j] * h[j] * S_xx[j];
  return r;
}

}  // namespace

double fully_nonlinear_second_harmonic_m(double a, double k, double d, double B) {
  // Second-order expansion of the residual above on sin(2 theta), with c0 eliminated by the linear
  // dispersion relation (derived symbolically; checked against the exact steady waves in
  // tests/boussinesq/boussinesq_nonlinear_test.cpp).
  const double x2 = k * d * k * d;
  return a * a * (9.0 + (45.0 * B + 3.0) * x2 + (36.0 * B * B + 8.0 * B) * x2 * x2) / (12.0 * k * k * d * d * d);
}

double stokes_second_harmonic_m(double a, double k, double d) {
  const double kd = k * d;
  return 0.25 * k * a * a * std::cosh(kd) * (2.0 + std::cosh(2.0 * kd)) / std::pow(std::sinh(kd), 3);
}

double boussinesq_second_harmonic_m(double a, double k, double d, double B, DispersionDepth depth_kind) {
  // eta = a cos(theta) + a2 cos(2 theta), P = c eta (mass with no mean flux), theta = k x - w t.
  // The momentum residual divided by k, r = -c^2 eta' + c^2 (eta^2/h)' + g h eta' + K(D) eta''',
  // K(D) = k^2 ((B+1/3) D^2 c^2 - B g D^3), at order a^2 on sin(2 theta):
  //   linear part 2 (c0^2 - g d) a2 + 8 K(d) a2 = 6 (g d - c0^2) a2   (K(d) = g d - c0^2 from order a),
  //   forcing    -(c0^2/d + g/2) a^2, and with D = h also + k^2 (2 d (B+1/3) c0^2 - 3 B g d^2) a^2 / 2.
  const double c2 = linear_phase_speed_squared(k, d, B);
  double forcing = c2 / d + 0.5 * g;
  if (depth_kind == DispersionDepth::kTotal)
    forcing -= 0.5 * k * k * (2.0 * d * (B + 1.0 / 3.0) * c2 - 3.0 * B * g * d * d);
  return a * a * forcing / (6.0 * (g * d - c2));
}

double stokes_frequency_increase(double a, double k, double d) {
  const double s = std::tanh(k * d), s4 = s * s * s * s, ka = k * a;
  return ka * ka * ((9.0 - 10.0 * s * s + 9.0 * s4) / (16.0 * s4) - 1.0 / (2.0 * s * k * d));
}

namespace {

// The Newton solve behind boussinesq_steady_wave (uncached).
SteadyWave solve_steady_wave(double a, double k, double d, double B, DispersionDepth depth_kind, int harmonic_count,
                             Equations equations) {
  const int N = std::max(2, harmonic_count), M = 8 * N;  // quadrature points: products de-aliased
  const double B3 = B + 1.0 / 3.0;
  // cos(n theta_j) and sin(n theta_j) once: Newton evaluates the residual (N + 1) times an
  // iteration, and the bake's wave maker and the structure flume ask for this wave many times.
  std::vector<double> cos_nj(static_cast<std::size_t>(N) * M), sin_nj(static_cast<std::size_t>(N) * M);
  for (int n = 1; n <= N; ++n)
    for (int j = 0; j < M; ++j) {
      const double angle = n * 2.0 * std::numbers::pi * j / M;
      cos_nj[static_cast<std::size_t>(n - 1) * M + j] = std::cos(angle);
      sin_nj[static_cast<std::size_t>(n - 1) * M + j] = std::sin(angle);
    }
  auto cos_of = [&](int n, int j) { return cos_nj[static_cast<std::size_t>(n - 1) * M + j]; };
  auto sin_of = [&](int n, int j) { return sin_nj[static_cast<std::size_t>(n - 1) * M + j]; };
  const QuadratureAngles angles(M);
  // Unknowns x = (c, a_2 .. a_N); residual R_m = projection of r(theta) on sin(m theta), m = 1..N
  // (r is odd in theta for a wave symmetric about its crest, so these are all its components).
  auto residual = [&](const Eigen::VectorXd& x, double a1) {
    const double c = x[0], c2 = c * c;
    Eigen::VectorXd R = Eigen::VectorXd::Zero(N);
    if (equations == Equations::kFullyNonlinear) {
      std::vector<double> eta(M, 0.0);
      for (int j = 0; j < M; ++j)
        for (int n = 1; n <= N; ++n) eta[j] += (n == 1 ? a1 : x[n - 1]) * cos_of(n, j);
      const std::vector<double> r = fully_nonlinear_residual(eta, c, k, d, B, angles);
      for (int j = 0; j < M; ++j)
        for (int m = 1; m <= N; ++m) R[m - 1] += 2.0 / M * r[j] * sin_of(m, j) / k;
      return R;
    }
    for (int j = 0; j < M; ++j) {
      double eta = 0, eta_1 = 0, eta_3 = 0;
      for (int n = 1; n <= N; ++n) {
        const double amplitude = n == 1 ? a1 : x[n - 1];
        eta += amplitude * cos_of(n, j);
        eta_1 -= n * amplitude * sin_of(n, j);
        eta_3 += n * n * n * amplitude * sin_of(n, j);
      }
      const double h = d + eta, D = depth_kind == DispersionDepth::kTotal ? h : d;
      const double r = -c2 * eta_1 + c2 * eta_1 * eta * (2.0 * d + eta) / (h * h) + g * h * eta_1 +
                       k * k * (B3 * D * D * c2 - B * g * D * D * D) * eta_3;
      for (int m = 1; m <= N; ++m) R[m - 1] += 2.0 / M * r * sin_of(m, j);
    }
    return R;
  };
  Eigen::VectorXd x = Eigen::VectorXd::Zero(N);
  x[0] = std::sqrt(linear_phase_speed_squared(k, d, B));
  // Continuation in amplitude from the linear wave: each step starts Newton close to its answer.
  constexpr int kSteps = 8;
  for (int step = 1; step <= kSteps; ++step) {
    const double a1 = a * step / kSteps;
    bool converged = false;
    for (int iteration = 0; iteration < 40 && !converged; ++iteration) {
      const Eigen::VectorXd R = residual(x, a1);
      Eigen::MatrixXd J(N, N);
      for (int u = 0; u < N; ++u) {
        Eigen::VectorXd xp = x;
        const double delta = u == 0 ? 1e-7 * x[0] : 1e-7 * a1;
        xp[u] += delta;
        J.col(u) = (residual(xp, a1) - R) / delta;
      }
      const Eigen::VectorXd dx = J.fullPivLu().solve(-R);
      x += dx;
      converged = std::abs(dx[0]) < 1e-13 * x[0] && dx.tail(N - 1).cwiseAbs().maxCoeff() < 1e-13 * a1 + 1e-300;
    }
    if (!converged || !std::isfinite(x[0]))
      throw Error("boussinesq_steady_wave",
                  fmt::format("no steady wave of amplitude {} m at k d = {} in depth {} m (Newton did not converge at {} m)",
                              a, k * d, d, a1),
                  "the wave is beyond the reach of the equations: ask for a smaller amplitude");
  }
  SteadyWave wave;
  wave.phase_speed_m_s = x[0];
  wave.harmonics_m.assign(N, 0.0);
  wave.harmonics_m[0] = a;
  for (int n = 2; n <= N; ++n) wave.harmonics_m[n - 1] = x[n - 1];
  return wave;
}

// The arguments of one solve, bit for bit (a cached wave is the wave those exact doubles give).
struct SteadyWaveKey {
  std::array<std::uint64_t, 4> values{};
  int depth_kind = 0, harmonic_count = 0, equations = 0;
  bool operator==(const SteadyWaveKey&) const = default;
};

}  // namespace

SteadyWave boussinesq_steady_wave(double a, double k, double d, double B, DispersionDepth depth_kind,
                                  int harmonic_count, Equations equations) {
  // A solve of the fully nonlinear equations is about 11 ms of CPU (a few hundred residuals of ten
  // spectral derivatives each; 0.5 ms for the weakly nonlinear ones), and a bake asks for the same
  // waves hundreds of times: the wave maker's height iteration (WaveMaker::second_order, seven
  // solves) each time a source is made, reading the case, every run of every structure's flume,
  // every state of a library at the same depth. A pure function of its arguments, so a process-wide memo
  // of the last solves returns exactly what a new solve would (failures are not kept: they throw).
  const SteadyWaveKey key{{std::bit_cast<std::uint64_t>(a), std::bit_cast<std::uint64_t>(k),
                           std::bit_cast<std::uint64_t>(d), std::bit_cast<std::uint64_t>(B)},
                          static_cast<int>(depth_kind), harmonic_count, static_cast<int>(equations)};
  constexpr std::size_t kKept = 256;
  static std::mutex mutex;
  static std::vector<std::pair<SteadyWaveKey, SteadyWave>> solved;  // oldest first
  {
    const std::lock_guard lock(mutex);
    for (const auto& [known, wave] : solved)
      if (known == key) return wave;
  }
  SteadyWave wave = solve_steady_wave(a, k, d, B, depth_kind, harmonic_count, equations);
  const std::lock_guard lock(mutex);
  if (solved.size() == kKept) solved.erase(solved.begin());
  solved.emplace_back(key, wave);
  return wave;
}

}  // namespace nearshore::boussinesq
