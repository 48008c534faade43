#pragma once
// Beaufort presets 0-12 (issue 5): wind force -> a wavenumber spectrum for the deep-water field,
// from seed 000 table 3.1 (wind speed range and wave height per force). As the seed does
// (section 3.1.1), low forces use the Phillips spectrum and high forces the unified spectrum
// (Phillips cannot show the long swell-like waves of a strong wind); the choice is overridable.
//
// The table's wave height is taken as the significant wave height Hs. Each preset reaches it:
//  - Phillips: the amplitude A is set from Hs (A = Hs^2 / (8 pi Lw^2), spectrum_wavenumber.hpp);
//  - unified: the wind speed fixes everything but the sea's development, so the inverse wave age
//    Omega_c (equivalently the fetch, seed 000 eq. 2.8) is solved for in [0.84, 5] so that the
//    spectrum's 4 sqrt(m0) = Hs. Where the table's height exceeds the fully developed sea's
//    (Omega_c = 0.84 reached), the preset keeps 0.84 and says so in `note`.
#include <array>
#include <memory>
#include <string>

#include "nearshore/ocean/spectrum_wavenumber.hpp"

namespace nearshore::ocean {

/// One row of seed 000 table 3.1.
struct BeaufortRow {
  int force = 0;
  double min_wind_km_h = 0.0, max_wind_km_h = 0.0;  ///< max = min for force 12 ("118 and above")
  const char* name = "";
  double wave_height_m = 0.0;
};

/// The table (force 4's range is printed "10-30" in the seed, a misprint for 20-30: the rows
/// around it are 13-19 and 31-40).
const std::array<BeaufortRow, 13>& beaufort_table();

enum class BeaufortSpectrum {
  kSeedChoice,  ///< Phillips for forces 0-4, unified for 5-12 (seed 000 section 3.1.1)
  kPhillips,
  kUnified,
};

struct BeaufortPreset {
  int force = 0;
  double wind_speed_10_m_s = 0.0;        ///< the middle of the table's range (force 12: 0.836 B^1.5 m/s = 34.8)
  double wind_direction_rad = 0.0;       ///< direction the wind blows TOWARDS (= the waves' travel)
  double table_wave_height_m = 0.0;      ///< the table's height
  std::shared_ptr<const WavenumberSpectrum> spectrum;  ///< null for force 0 (a calm, flat sea)
  double inverse_wave_age = 0.0;         ///< unified only
  double fetch_m = 0.0;                  ///< unified only (infinity = fully developed)
  std::string note;                      ///< why the preset deviates from the table, if it does
};

/// A wind as charts and sailors give it, the compass bearing it blows FROM (degrees, clockwise
/// from north), turned into the direction its waves travel TOWARD, counter-clockwise from east
/// (radians): the convention of every spectrum and preset here.
inline double travel_direction_rad(double wind_from_compass_deg) {
  return (90.0 - (wind_from_compass_deg + 180.0)) * 3.14159265358979323846 / 180.0;
}

/// The preset for `force` (0-12; anything else is a nearshore::Error naming the fix).
BeaufortPreset beaufort_preset(int force, double wind_direction_rad = 0.0,
                               BeaufortSpectrum choice = BeaufortSpectrum::kSeedChoice);

}  // namespace nearshore::ocean
