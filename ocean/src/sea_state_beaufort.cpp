#include "nearshore/ocean/sea_state_beaufort.hpp"

#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "nearshore/ocean/spectrum.hpp"
#include "nearshore/core/error.hpp"

namespace nearshore::ocean {

const std::array<BeaufortRow, 13>& beaufort_table() {
  // seed 000 table 3.1: force, wind (km/h), name, wave height (m).
  static const std::array<BeaufortRow, 13> table = {{
      {0, 0.0, 2.0, "Calm", 0.0},
      {1, 2.0, 6.0, "Light air", 0.1},
      {2, 7.0, 12.0, "Light breeze", 0.2},
      {3, 13.0, 19.0, "Gentle breeze", 0.6},
      {4, 20.0, 30.0, "Moderate breeze", 1.0},
      {5, 31.0, 40.0, "Fresh breeze", 2.0},
      {6, 41.0, 51.0, "Strong breeze", 3.0},
      {7, 52.0, 62.0, "Near gale", 4.0},
      {8, 63.0, 75.0, "Gale", 5.5},
      {9, 76.0, 87.0, "Strong gale", 7.0},
      {10, 88.0, 103.0, "Storm", 9.0},
      {11, 104.0, 117.0, "Violent storm", 11.5},
      {12, 118.0, 118.0, "Hurricane", 14.0},
  }};
  return table;
}

namespace {

/// Omega_c in [0.84, 5] with 4 sqrt(m0) of the unified spectrum = hs (bisection: Hs falls as the
/// sea gets younger, i.e. as Omega_c grows). Returns 0.84 when even the developed sea is lower.
double inverse_wave_age_for(double u10, double hs_m, double direction_rad) {
  auto hs_at = [&](double omega_c) { return UnifiedSpectrum(u10, omega_c, direction_rad).significant_wave_height_m(); };
  double low = 0.84, high = 5.0;
  if (hs_at(low) <= hs_m) return low;
  if (hs_at(high) >= hs_m) return high;
  for (int iteration = 0; iteration < 50; ++iteration) {
    const double middle = 0.5 * (low + high);
    (hs_at(middle) > hs_m ? low : high) = middle;
  }
  return 0.5 * (low + high);
}

}  // namespace

BeaufortPreset beaufort_preset(int force, double wind_direction_rad, BeaufortSpectrum choice) {
  if (force < 0 || force > 12)
    throw Error("Beaufort preset", fmt::format("force {} is not on the Beaufort scale", force),
                "give a force from 0 (calm) to 12 (hurricane)");
  const BeaufortRow& row = beaufort_table()[force];
  BeaufortPreset preset;
  preset.force = force;
  preset.wind_direction_rad = wind_direction_rad;
  preset.table_wave_height_m = row.wave_height_m;
  // Middle of the range; force 12 has no upper bound: the Beaufort relation v = 0.836 B^(3/2) m/s.
  preset.wind_speed_10_m_s = force == 12 ? 0.836 * std::pow(12.0, 1.5) : 0.5 * (row.min_wind_km_h + row.max_wind_km_h) / 3.6;
  if (row.wave_height_m <= 0.0) {
    preset.note = "calm: no waves";
    return preset;
  }
  const bool phillips = choice == BeaufortSpectrum::kPhillips || (choice == BeaufortSpectrum::kSeedChoice && force <= 4);
  if (phillips) {
    // Phillips is scale-free: A fixes the steepness, Lw = U^2/g the size. At forces 1-3 the
    // table's height is more than a fully developed sea reaches at the table's wind
    // (Hs = 0.209 U^2 / g, PM): with that wind the sea would be steeper than any wind sea
    // (Hs kp = 0.66 at force 1). There the length scale comes from the height instead: the wind
    // whose developed sea has the table's height.
    const double developed_hs = PiersonMoskowitzSpectrum::from_wind_speed(preset.wind_speed_10_m_s).significant_wave_height_m();
    double phillips_wind = preset.wind_speed_10_m_s;
    if (row.wave_height_m > developed_hs) {
      phillips_wind *= std::sqrt(row.wave_height_m / developed_hs);  // Hs grows as U^2
      preset.note = fmt::format("Phillips length scale from a {:.2f} m/s wind: at the table's {:.2f} m/s a developed "
                                "sea is only {:.2f} m high",
                                phillips_wind, preset.wind_speed_10_m_s, developed_hs);
    }
    const double amplitude = PhillipsSpectrum::amplitude_for_significant_wave_height(row.wave_height_m, phillips_wind);
    preset.spectrum = std::make_shared<PhillipsSpectrum>(amplitude, phillips_wind, wind_direction_rad);
    return preset;
  }
  preset.inverse_wave_age = inverse_wave_age_for(preset.wind_speed_10_m_s, row.wave_height_m, wind_direction_rad);
  preset.fetch_m = UnifiedSpectrum::fetch_from_inverse_wave_age(preset.wind_speed_10_m_s, preset.inverse_wave_age);
  auto unified = std::make_shared<UnifiedSpectrum>(preset.wind_speed_10_m_s, preset.inverse_wave_age, wind_direction_rad);
  const double hs = unified->significant_wave_height_m();
  if (std::abs(hs - row.wave_height_m) > 0.01 * row.wave_height_m)
    preset.note = fmt::format("the unified spectrum at {:.1f} m/s reaches Hs = {:.2f} m at Omega_c = {:.2f}, not the "
                              "table's {:.1f} m",
                              preset.wind_speed_10_m_s, hs, preset.inverse_wave_age, row.wave_height_m);
  preset.spectrum = std::move(unified);
  return preset;
}

}  // namespace nearshore::ocean
