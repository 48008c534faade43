#include "nearshore/ocean/sea_state_builder.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include <fmt/format.h>

#include "nearshore/ocean/spectrum_quadrature.hpp"
#include "nearshore/core/error.hpp"

namespace nearshore::ocean {
namespace {

constexpr double kPi = std::numbers::pi;
const char* const kSubject = "sea-state specification";

/// The band [w_low, w_high] that holds `kept` of the spectrum's variance, one fifth of the rest
/// cut below and four fifths above (the w^-5 tail is the long side).
std::pair<double, double> automatic_band(const FrequencySpectrum& spectrum, double kept) {
  const double wp = spectrum.peak_angular_frequency_rad_s();
  constexpr int samples = 4000;
  const double low = 0.05 * wp, ratio = std::pow(4000.0, 1.0 / samples);  // 0.05 wp .. 200 wp
  std::vector<double> edge(samples + 1), cumulative(samples + 1, 0.0);
  edge[0] = low;
  for (int i = 1; i <= samples; ++i) {
    edge[i] = edge[i - 1] * ratio;
    cumulative[i] = cumulative[i - 1] + integrate_gauss_legendre(
        [&](double w) { return spectrum.density_m2_s_rad(w); }, edge[i - 1], edge[i], 1);
  }
  const double total = cumulative.back();
  auto quantile = [&](double fraction) {
    const double target = fraction * total;
    const auto it = std::lower_bound(cumulative.begin(), cumulative.end(), target);
    const std::size_t i = std::clamp<std::size_t>(it - cumulative.begin(), 1, samples);
    const double step = cumulative[i] - cumulative[i - 1];
    const double t = step > 0.0 ? (target - cumulative[i - 1]) / step : 0.0;
    return edge[i - 1] + t * (edge[i] - edge[i - 1]);
  };
  const double cut = 1.0 - kept;
  return {quantile(0.2 * cut), quantile(1.0 - 0.8 * cut)};
}

/// Edges of the frequency cells: equal cells over the band, or, with a loop period, cells cut
/// half-way between consecutive harmonics of 2 pi / T nearest the equal cells' centres.
struct FrequencyCells {
  std::vector<double> edge_rad_s;    // count + 1
  std::vector<double> centre_rad_s;  // count: the component frequencies
};

FrequencyCells frequency_cells(double w_low, double w_high, int count, double loop_period_s) {
  FrequencyCells cells;
  const double width = (w_high - w_low) / count;
  for (int j = 0; j <= count; ++j) cells.edge_rad_s.push_back(w_low + j * width);
  for (int j = 0; j < count; ++j) cells.centre_rad_s.push_back(w_low + (j + 0.5) * width);
  if (loop_period_s <= 0.0) return cells;

  const double fundamental = 2.0 * kPi / loop_period_s;
  std::vector<long long> harmonic;
  for (double centre : cells.centre_rad_s) harmonic.push_back(std::llround(centre / fundamental));
  for (std::size_t j = 0; j < harmonic.size(); ++j) {
    const bool repeated = j > 0 && harmonic[j] <= harmonic[j - 1];
    if (harmonic[j] < 1 || repeated)
      throw Error(kSubject,
                  fmt::format("loop period {} s gives harmonics 2 pi / T = {:.5f} rad/s apart, wider than the "
                              "{:.5f} rad/s frequency cells ({} cells over {:.4f}-{:.4f} rad/s)",
                              loop_period_s, fundamental, width, count, w_low, w_high),
                  fmt::format("lengthen the loop to at least {:.0f} s or use at most {} frequency components",
                              std::ceil(2.0 * kPi / width), static_cast<int>((w_high - w_low) / fundamental)));
  }
  for (int j = 0; j < count; ++j) cells.centre_rad_s[j] = static_cast<double>(harmonic[j]) * fundamental;
  // Interior edges half-way between harmonics; the band's ends stay where they are, so the cells
  // still tile [w_low, w_high] and no variance is lost or counted twice.
  for (int j = 1; j < count; ++j)
    cells.edge_rad_s[j] = 0.5 * (cells.centre_rad_s[j - 1] + cells.centre_rad_s[j]);
  return cells;
}

void check(const DirectionalSeaSpecification& spec) {
  if (!spec.spectrum) throw Error(kSubject, "has no frequency spectrum", "set .spectrum (e.g. a JonswapSpectrum)");
  if (!spec.spreading)
    throw Error(kSubject, "has no directional spreading", "set .spreading (e.g. CosineSquaredSpreading(mean, 15))");
  if (spec.frequency_count < 1 || spec.direction_count < 1)
    throw Error(kSubject,
                fmt::format("asks for {} frequencies x {} directions", spec.frequency_count, spec.direction_count),
                "use at least 1 of each");
  if (!(spec.kept_variance_fraction > 0.5 && spec.kept_variance_fraction < 1.0))
    throw Error(kSubject, fmt::format("kept_variance_fraction = {} is outside (0.5, 1)", spec.kept_variance_fraction),
                "use 0.995 (the default)");
  const bool manual_band = spec.min_frequency_rad_s > 0.0 || spec.max_frequency_rad_s > 0.0;
  if (manual_band && !(spec.max_frequency_rad_s > spec.min_frequency_rad_s && spec.min_frequency_rad_s > 0.0))
    throw Error(kSubject,
                fmt::format("frequency band [{}, {}] rad/s is empty or not positive", spec.min_frequency_rad_s,
                            spec.max_frequency_rad_s),
                "give 0 < min_frequency_rad_s < max_frequency_rad_s, or leave both 0 for the automatic band");
  if (spec.loop_period_s < 0.0 || !std::isfinite(spec.loop_period_s))
    throw Error(kSubject, fmt::format("loop period {} s is negative or not finite", spec.loop_period_s),
                "give T_loop > 0 s, or 0 for no exact looping");
  if (spec.direction_half_width_rad < 0.0 || spec.direction_half_width_rad > kPi)
    throw Error(kSubject, fmt::format("direction half-width {} rad is outside [0, pi]", spec.direction_half_width_rad),
                "give 0 (automatic) up to pi (the whole circle)");
}

}  // namespace

double phase_from_draw_rad(std::uint64_t draw) {
  return static_cast<double>(draw >> 11) * 0x1.0p-53 * 2.0 * kPi;
}

SeaState build_sea_state(const DirectionalSeaSpecification& spec) {
  check(spec);
  const FrequencySpectrum& spectrum = *spec.spectrum;
  const DirectionalSpreading& spreading = *spec.spreading;

  // 1. The frequency band and its cells.
  auto [w_low, w_high] = spec.min_frequency_rad_s > 0.0
                             ? std::pair{spec.min_frequency_rad_s, spec.max_frequency_rad_s}
                             : automatic_band(spectrum, spec.kept_variance_fraction);
  const FrequencyCells cells = frequency_cells(w_low, w_high, spec.frequency_count, spec.loop_period_s);

  // 2. The direction cells: equal cells over [mean - h, mean + h]; one cell = the whole circle
  //    collapsed onto the mean direction (long-crested).
  const double mean = spreading.mean_direction_rad();
  const bool long_crested = spec.direction_count == 1;
  const double half_width =
      long_crested ? kPi
                   : (spec.direction_half_width_rad > 0.0
                          ? spec.direction_half_width_rad
                          : spreading.half_width_holding_rad(0.999, spectrum.peak_angular_frequency_rad_s()));
  const double direction_width = 2.0 * half_width / spec.direction_count;

  // 3. One component per cell, a = sqrt(2 * integral of S D over the cell) (seed 001 eq. 16-17).
  //    The direction integral is taken at each frequency node because D may depend on w.
  // Panels no wider than 2 % of wp in frequency and 0.05 rad in direction: the JONSWAP peak
  // (sigma = 0.07 wp) and a cos^2s lobe (s = 75: width ~0.16 rad) are then smooth on every panel
  // of the 8-point rule, however wide the cell.
  const double wp = spectrum.peak_angular_frequency_rad_s();
  auto panels_for = [](double width, double finest) { return std::max(2, static_cast<int>(std::ceil(width / finest))); };
  const int direction_panels = panels_for(long_crested ? 2.0 * kPi : direction_width, 0.05);
  SeaState sea;
  sea.loop_period_s = spec.loop_period_s;
  sea.seed = spec.seed;
  std::mt19937_64 generator(spec.seed);
  sea.components.reserve(static_cast<std::size_t>(spec.frequency_count) * spec.direction_count);
  for (int j = 0; j < spec.frequency_count; ++j) {
    for (int m = 0; m < spec.direction_count; ++m) {
      const double theta0 = mean - half_width + m * direction_width;
      auto directional_density = [&](double w) {
        const double fraction = integrate_gauss_legendre(
            [&](double theta) { return spreading.density_per_rad(theta, w); }, theta0, theta0 + direction_width,
            direction_panels);
        return spectrum.density_m2_s_rad(w) * fraction;
      };
      const double variance_m2 = integrate_gauss_legendre(directional_density, cells.edge_rad_s[j],
                                                          cells.edge_rad_s[j + 1],
                                                          panels_for(cells.edge_rad_s[j + 1] - cells.edge_rad_s[j], 0.02 * wp));
      WaveComponent component;
      component.amplitude_m = std::sqrt(2.0 * std::max(variance_m2, 0.0));
      component.angular_frequency_rad_s = cells.centre_rad_s[j];
      component.direction_rad = wrap_angle_rad(theta0 + 0.5 * direction_width);
      component.phase_rad = phase_from_draw_rad(generator());
      sea.components.push_back(component);
    }
  }
  return sea;
}

SeaState regular_wave_sea_state(double height_m, double period_s, double direction_rad, double phase_rad) {
  if (!(height_m >= 0.0) || !(period_s > 0.0) || !std::isfinite(height_m) || !std::isfinite(period_s))
    throw Error("regular wave", fmt::format("height {} m / period {} s", height_m, period_s),
                "give a height >= 0 m and a period > 0 s");
  SeaState sea;
  sea.components.push_back(WaveComponent{0.5 * height_m, 2.0 * kPi / period_s, wrap_angle_rad(direction_rad),
                                         phase_rad});
  sea.loop_period_s = period_s;
  sea.seed = 0;
  return sea;
}

double significant_wave_height_m(const SeaState& sea) {
  double variance_m2 = 0.0;
  for (const WaveComponent& c : sea.components) variance_m2 += 0.5 * c.amplitude_m * c.amplitude_m;
  return 4.0 * std::sqrt(variance_m2);
}

}  // namespace nearshore::ocean
