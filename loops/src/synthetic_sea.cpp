#include "nearshore/loops/synthetic_sea.hpp"

#include <cmath>
#include <numbers>
#include <random>

#include <fmt/core.h>

#include "nearshore/core/error.hpp"
#include "nearshore/ocean/linear_waves.hpp"
#include "nearshore/ocean/spectrum.hpp"

namespace nearshore::loops {
namespace {

using ocean::LatticeWave;

// Hs = 4 sqrt(m0), m0 = sum a^2 / 2: scale amplitudes to the requested significant height.
void scale_to_significant_height(SyntheticSea& sea, double significant_height_m) {
  double m0 = 0;
  for (const LatticeWave& c : sea.components) m0 += 0.5 * c.wave.amplitude_m * c.wave.amplitude_m;
  const double scale = m0 > 0 ? significant_height_m / (4.0 * std::sqrt(m0)) : 0.0;
  for (LatticeWave& c : sea.components) c.wave.amplitude_m *= scale;
}

LatticeWave component(double omega, double direction_rad, double amplitude, double phase, double depth_m) {
  const double k = ocean::wavenumber_from_frequency(omega, depth_m);
  return LatticeWave{{amplitude, omega, direction_rad, phase}, k * std::cos(direction_rad), k * std::sin(direction_rad)};
}

}  // namespace

double linear_dispersion_omega_rad_s(double wavenumber_rad_m, double depth_m) {
  return ocean::frequency_from_wavenumber(wavenumber_rad_m, depth_m);
}

SyntheticSea periodic_sea(double period_s, int component_count, double significant_height_m, double depth_m,
                          std::uint64_t seed) {
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  SyntheticSea sea{depth_m, {}};
  for (int n = 1; n <= component_count; ++n) {
    const double omega = 2 * std::numbers::pi * n / period_s;  // harmonic n: period_s / n divides period_s
    const double direction = (uniform(random) - 0.5) * 1.4;
    sea.components.push_back(component(omega, direction, 1.0 / n, 2 * std::numbers::pi * uniform(random), depth_m));
  }
  scale_to_significant_height(sea, significant_height_m);
  return sea;
}

SyntheticSea irregular_sea(double peak_period_s, int component_count, double significant_height_m, double depth_m,
                           double mean_direction_rad, std::uint64_t seed) {
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  SyntheticSea sea{depth_m, {}};
  const double peak_omega = 2 * std::numbers::pi / peak_period_s;
  // Only the shape matters (amplitudes are scaled to Hs below): JONSWAP with gamma 3.3.
  const ocean::JonswapSpectrum jonswap(significant_height_m > 0 ? significant_height_m : 1.0, peak_period_s, 3.3);
  for (int n = 0; n < component_count; ++n) {
    // Frequencies spread over 0.6..2.5 omega_p, jittered so no two are commensurate.
    const double omega = peak_omega * (0.6 + 1.9 * (n + uniform(random)) / component_count);
    const double spectrum = jonswap.density_m2_s_rad(omega);
    const double direction = mean_direction_rad + (uniform(random) - 0.5) * 2 * (40.0 * std::numbers::pi / 180.0);
    sea.components.push_back(
        component(omega, direction, std::sqrt(spectrum), 2 * std::numbers::pi * uniform(random), depth_m));
  }
  scale_to_significant_height(sea, significant_height_m);
  return sea;
}

void evaluate_sea(const SyntheticSea& sea, const GridGeometry& geometry, double time_s, Raster<float>& eta,
                  Raster<float>& flux_x, Raster<float>& flux_y) {
  const int columns = geometry.columns, rows = geometry.rows;
  eta = Raster<float>(columns, rows);
  flux_x = Raster<float>(columns, rows);
  flux_y = Raster<float>(columns, rows);
  std::vector<double> e(static_cast<std::size_t>(columns)), p(e.size()), q(e.size());
  for (int row = 0; row < rows; ++row) {
    std::fill(e.begin(), e.end(), 0.0);
    std::fill(p.begin(), p.end(), 0.0);
    std::fill(q.begin(), q.end(), 0.0);
    const double y = geometry.cell_centre_y_m(row) - geometry.origin_y_m;
    for (const LatticeWave& lattice : sea.components) {
      const ocean::WaveComponent& c = lattice.wave;
      const double kx = lattice.wavenumber_x_rad_m, ky = lattice.wavenumber_y_rad_m;
      const double k = std::hypot(kx, ky);
      const double speed = c.angular_frequency_rad_s / k;  // omega / k: depth-integrated u per unit eta
      const double ux = speed * kx / k, uy = speed * ky / k;
      // cos(phi0 + kx * column * dx) by rotation, so the inner loop has no trigonometry.
      const double phase0 = kx * (0.5 * geometry.spacing_m) + ky * y -
                            c.angular_frequency_rad_s * time_s + c.phase_rad;
      const double step = kx * geometry.spacing_m;
      double cr = std::cos(phase0), ci = std::sin(phase0);
      const double sr = std::cos(step), si = std::sin(step);
      for (int column = 0; column < columns; ++column) {
        const double value = c.amplitude_m * cr;
        e[column] += value;
        p[column] += ux * value;
        q[column] += uy * value;
        const double next = cr * sr - ci * si;
        ci = cr * si + ci * sr;
        cr = next;
      }
    }
    for (int column = 0; column < columns; ++column) {
      eta(column, row) = static_cast<float>(e[column]);
      flux_x(column, row) = static_cast<float>(p[column]);
      flux_y(column, row) = static_cast<float>(q[column]);
    }
  }
}

void write_sea_sequence(const std::filesystem::path& folder, const SyntheticSea& sea, const GridGeometry& geometry,
                        int frame_count, double frame_interval_s, double loop_period_s,
                        sequence::FrameEncoding encoding) {
  sequence::SequenceDescription description;
  description.frame_interval_s = frame_interval_s;
  description.loop_period_s = loop_period_s;
  description.encoding = encoding;
  nlohmann::json components = nlohmann::json::array();
  for (const ocean::LatticeWave& c : sea.components)
    components.push_back({{"amplitude_m", c.wave.amplitude_m}, {"kx_rad_m", c.wavenumber_x_rad_m},
                          {"ky_rad_m", c.wavenumber_y_rad_m}, {"omega_rad_s", c.wave.angular_frequency_rad_s},
                          {"phase_rad", c.wave.phase_rad}});
  description.wave_conditions = {{"kind", "synthetic linear sea"}, {"components", components}};
  sequence::SequenceWriter writer(folder, HarbourGrid::open_water(geometry, static_cast<float>(sea.still_water_depth_m)),
                                  description);
  Raster<float> eta, p, q;
  for (int index = 0; index < frame_count; ++index) {
    evaluate_sea(sea, geometry, index * frame_interval_s, eta, p, q);
    writer.write_frame(index, {&eta, &p, &q, nullptr});
  }
  writer.finish(frame_count);
}

void write_planted_repeat_sequence(const std::filesystem::path& folder, const GridGeometry& geometry, int frame_count,
                                   int repeat_source, int repeat_copy, int repeat_length, double step_rms_m,
                                   std::uint64_t seed) {
  if (repeat_source < 0 || repeat_source + repeat_length > repeat_copy || repeat_copy + repeat_length > frame_count)
    throw Error(folder.string(), fmt::format("planted repeat {}+{} -> {} does not fit {} frames", repeat_source,
                                             repeat_length, repeat_copy, frame_count),
                "choose source < copy and copy + length <= frames");
  sequence::SequenceDescription description;
  description.frame_interval_s = 0.1;
  description.seed = seed;
  description.encoding = {sequence::Compression::kZip, sequence::Precision::kFloat, sequence::Precision::kFloat,
                          sequence::Precision::kFloat};
  description.wave_conditions = {{"kind", "random walk with planted repeat"}, {"repeat_source", repeat_source},
                                 {"repeat_copy", repeat_copy}, {"repeat_length", repeat_length}};
  sequence::SequenceWriter writer(folder, HarbourGrid::open_water(geometry, 10.0f), description);
  std::mt19937_64 random(seed);
  std::normal_distribution<float> noise(0.0f, static_cast<float>(step_rms_m));
  std::vector<std::array<Raster<float>, 3>> frames(static_cast<std::size_t>(frame_count));
  std::array<Raster<float>, 3> state;
  for (auto& field : state) field = Raster<float>(geometry.columns, geometry.rows);
  for (int index = 0; index < frame_count; ++index) {
    if (index >= repeat_copy && index < repeat_copy + repeat_length) {
      state = frames[static_cast<std::size_t>(repeat_source + index - repeat_copy)];
    } else {
      for (auto& field : state)
        for (float& value : field.values()) value += noise(random);
    }
    frames[static_cast<std::size_t>(index)] = state;
    writer.write_frame(index, {&state[0], &state[1], &state[2], nullptr});
  }
  writer.finish(frame_count);
}

}  // namespace nearshore::loops
