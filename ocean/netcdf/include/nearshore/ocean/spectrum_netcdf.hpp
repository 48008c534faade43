#pragma once
// Frequency-direction spectra from wave models' NetCDF output (issue 46), read into the same
// SampledDirectionalSpectrum as the ASCII formats of spectrum_files.hpp. A target of its own
// (nearshore_ocean_netcdf, linked by the bake side only), so that the runtime, which links
// nearshore_ocean, never links libnetcdf.
//
// Two layouts, one reader (names as the models write them):
//  - WAVEWATCH III point output (ww3_ounp, NetCDF): efth(time, station, frequency, direction) in
//    "m2 s rad-1", `frequency` in s-1, `direction` in degree with standard_name
//    sea_surface_wave_to_direction: the direction waves travel TO, nautical (clockwise from north),
//    so theta = 90 deg - direction.
//  - SWAN's NetCDF spectral output (SPECOUT ... SPEC2D to a .nc file): the 2-D variance density
//    `density` (or `energy`) over (time, points, frequency, direction) in m2/Hz/degr (or per rad),
//    `direction` with standard_name sea_surface_wave_from_direction (SWAN's NDIR, nautical: the
//    direction waves come FROM, clockwise from north, theta = 270 deg - direction) or
//    sea_surface_wave_to_direction (SWAN's CDIR, Cartesian: theta = direction).
// The variable's dimensions are found by name, in any order: one containing "freq", one "dir", an
// optional "time", and at most one other (the location: station, points). Units per degree are
// multiplied by 180 / pi; per rad kept; anything else (an energy density in J) is refused.
// scale_factor / add_offset are applied; a _FillValue at the chosen point is refused.
#include <cstddef>
#include <filesystem>

#include "nearshore/ocean/spectrum_files.hpp"

namespace nearshore::ocean {

enum class NetcdfSpectrumLayout { kWavewatch3, kSwan };

struct NetcdfSpectrumSelection {
  NetcdfSpectrumLayout layout = NetcdfSpectrumLayout::kWavewatch3;
  std::size_t location_index = 0;  ///< 0-based along the station / points dimension
  std::size_t time_index = 0;      ///< 0-based along the time dimension
};

/// Reads one location at one time. Throws nearshore::Error naming the file, the variable and the fix
/// for a file that is not NetCDF, a missing variable or dimension, an index beyond its dimension,
/// units that are not a variance density, a direction convention it cannot tell, or missing values.
SampledDirectionalSpectrum read_netcdf_spectrum(const std::filesystem::path& nc_path, const NetcdfSpectrumSelection& selection);

}  // namespace nearshore::ocean
