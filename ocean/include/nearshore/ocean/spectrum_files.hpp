#pragma once
// Spectra from wave models and buoys (issue 46): a frequency-direction spectrum read from a file,
// and the sea state built from it by the same builder (and the same loop-exact frequencies) as a
// parametric spectrum.
//
// Two formats are read:
//  - SWAN's ASCII 2-D spectral output (`.sp2`), as the SWAN user manual's appendix D, "Spectrum
//    files, input and output", writes it: the `SWAN` line, `$` comments, optional `TIME`,
//    `LONLAT` or `LOCATIONS`, `AFREQ` or `RFREQ`, `NDIR` or `CDIR`, `QUANT` (one quantity,
//    `VaDens` m2/Hz/degr or `EnDens` J/m2/Hz/degr), and per time and location a `FACTOR` with the
//    integer matrix (one row per frequency, one column per direction), `NODATA` or `ZERO`.
//  - An NDBC buoy's spectrum with its directional moments, as the five realtime2 files hold them
//    (www.ndbc.noaa.gov/data_spec.shtml, measdes.shtml): the spectral density `.data_spec` (m2/Hz),
//    the mean direction alpha1 `.swdir`, the principal direction alpha2 `.swdir2`, and r1 `.swr1`,
//    r2 `.swr2`; the direction distribution is the truncated Fourier series NDBC gives
//    (Longuet-Higgins, Cartwright & Smith 1963):
//      D(f, a) = 1/pi (1/2 + r1 cos(a - alpha1) + r2 cos(2 (a - alpha2)))   (per radian).
//
// Conventions. The project's direction is the direction waves TRAVEL, counter-clockwise from +x
// (east) (wave_component.hpp). SWAN's CDIR is that same Cartesian convention (degrees); SWAN's
// NDIR and NDBC's alpha are nautical: the direction waves COME FROM, clockwise from north, so
//   theta = 270 deg - nautical  (wrapped to (-180, 180] deg).
// Densities are stored per Hz and per radian: SWAN's per-degree values are multiplied by
// 180 / pi, EnDens is divided by rho g (rho = 1025 kg/m3, SWAN's default, unless the caller says).
#include <cstddef>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "nearshore/ocean/sea_state_builder.hpp"
#include "nearshore/ocean/spectrum.hpp"

namespace nearshore::ocean {

/// A discretised frequency-direction spectrum E(f, theta) as a file gives it.
struct SampledDirectionalSpectrum {
  std::vector<double> frequencies_hz;     ///< strictly increasing, > 0
  std::vector<double> directions_rad;     ///< direction of travel, CCW from east, in (-pi, pi], increasing
  std::vector<double> density_m2_hz_rad;  ///< [frequency * directions + direction], >= 0
  std::string source;                     ///< "file.sp2, location 1, time 20020101.000000" for messages

  double density(std::size_t frequency_index, std::size_t direction_index) const {
    return density_m2_hz_rad[frequency_index * directions_rad.size() + direction_index];
  }
};

/// What to take from a SWAN `.sp2` file.
struct SwanSpectrumSelection {
  std::size_t location_index = 0;       ///< 0-based, in the order of the LONLAT / LOCATIONS block
  std::string time;                     ///< "20020101.000000" as the file writes it; empty = the first time
  double water_density_kg_m3 = 1025.0;  ///< rho, to turn EnDens (J/m2/Hz/degr) into variance
};

/// Reads one location at one time of a SWAN 2-D spectral file. Throws nearshore::Error naming the
/// file, the line and the fix for a missing block, wrong counts, a non-number, a negative density
/// (the exception value included), NODATA at the chosen location, a time that is not there, or a
/// 1-D (`.sp1`) file.
SampledDirectionalSpectrum read_swan_spectrum(const std::filesystem::path& sp2_path,
                                              const SwanSpectrumSelection& selection = {});

/// The five NDBC realtime2 files of one buoy.
struct NdbcSpectrumFiles {
  std::filesystem::path spectral_density;     ///< `.data_spec` (swden): m2/Hz per frequency
  std::filesystem::path mean_direction;       ///< `.swdir`: alpha1, degrees, nautical (from)
  std::filesystem::path principal_direction;  ///< `.swdir2`: alpha2, degrees, nautical (from)
  std::filesystem::path first_coefficient;    ///< `.swr1`: r1 in [0, 1]
  std::filesystem::path second_coefficient;   ///< `.swr2`: r2 in [0, 1]
};

struct NdbcSpectrumSelection {
  std::string time;          ///< "YYYY MM DD hh mm" as the files write it; empty = the first row
  int direction_count = 72;  ///< directions the Fourier series is sampled at (5 degrees apart)
};

/// Reads one time of an NDBC buoy's five files and spreads each frequency's density over the
/// circle by the truncated Fourier series above. Where the series dips below zero (narrow spectra:
/// r2 near 1) it is cut at zero and the rest scaled back to a unit integral, so each frequency keeps
/// its measured density and Hs stays the buoy's. Throws nearshore::Error naming the file, the line
/// and the fix for a missing time, frequencies that differ between the files, missing values (999)
/// where there is energy, r outside [0, 1], or a non-number.
SampledDirectionalSpectrum read_ndbc_spectrum(const NdbcSpectrumFiles& files,
                                              const NdbcSpectrumSelection& selection = {});

/// m0 = integral E df dtheta (m^2): trapezoids in frequency over the file's band (nothing outside
/// it) and the periodic trapezoid rule in direction, i.e. the exact integral of the bilinear
/// interpolation the sea-state builder sees.
double zeroth_moment_m2(const SampledDirectionalSpectrum& spectrum);
/// Hs = 4 sqrt(m0) (m).
double significant_wave_height_m(const SampledDirectionalSpectrum& spectrum);
/// Tp = 1 / the file frequency with the largest E(f) (s).
double peak_period_s(const SampledDirectionalSpectrum& spectrum);
/// The energy-weighted circular mean direction of travel atan2(sum E sin, sum E cos) (rad).
double mean_direction_rad(const SampledDirectionalSpectrum& spectrum);

/// Checks the invariants of SampledDirectionalSpectrum (sizes, order, finite non-negative
/// densities, some energy, directions around the whole circle); throws nearshore::Error naming
/// `spectrum.source`.
void check_sampled_spectrum(const SampledDirectionalSpectrum& spectrum);

/// The file's spectrum as the builder's pair: S(w) = E_f(w / 2 pi) / 2 pi from the direction
/// integral of the linear interpolation in frequency (0 outside the file's band), and
/// D(theta; w) = E(f, theta) / E_f(f) from the bilinear interpolation (periodic in theta), and
/// the band and direction half-width that hold the whole file:
///   min/max frequency = the file's first/last frequency, so the cells tile the file's band and
///   the components carry its m0 (Hs = 4 sqrt(m0) kept, not the 99.5 % of a parametric band);
///   the half-width around the mean that holds all but 1e-4 of m0.
/// The caller sets the counts, the loop period and the seed as for a parametric sea.
DirectionalSeaSpecification sea_specification_from_sampled(
    std::shared_ptr<const SampledDirectionalSpectrum> spectrum);

}  // namespace nearshore::ocean
