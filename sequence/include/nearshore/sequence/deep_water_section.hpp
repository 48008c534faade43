#pragma once
// The deep-water FFT field a bake carries for the runtime (docs/deep-water.md): the manifest's
// `deep_water` section as typed records, and the coefficient files deep_water_cascade_<i>.bin
// written beside the frames. Part of the sequence contract: the bake writes these and the runtime
// reads them, and no code outside sequence/ spells their keys or bytes.
//
// The field itself (synthesis, cascades, foam) is ocean/deep_water.hpp; this file holds what is on
// disk. The section's format string is "nearshore deep water 1"; an unknown one is refused.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "nearshore/sequence/file_entry.hpp"

namespace nearshore::sequence {

inline constexpr const char* kDeepWaterSectionFormat = "nearshore deep water 1";

/// One cascade of the field: its tile, wavenumber band and what it carries.
struct DeepWaterCascadeRecord {
  double tile_length_m = 0.0;
  int grid_size = 0;                    ///< N samples per tile side
  double min_wavenumber_rad_m = 0.0;    ///< inclusive
  double max_wavenumber_rad_m = 0.0;    ///< exclusive
  double variance_m2 = 0.0;             ///< sum a^2/2 of its components
  double slope_variance = 0.0;          ///< sum a^2 k^2/2
  std::optional<FileEntry> coefficients;  ///< deep_water_cascade_<i>.bin, when written beside the frames
};

/// The wave maker made of the field's waves (bake/deep_water_coupling.hpp), as recorded.
struct DeepWaterMakerRecord {
  std::uint64_t components = 0;
  double variance_fraction = 0.0;
  double field_variance_m2 = 0.0, carried_variance_m2 = 0.0;
  double carried_significant_wave_height_m = 0.0;
  double source_depth_m = 0.0;
  double min_frequency_hz = 0.0, max_frequency_hz = 0.0;
};

/// Where the runtime cross-fades from the FFT field (seaward) to the baked field (inland): distance
/// s inland of the source line along the maker's inward normal; the baked weight is w(s) = 0 for
/// s <= start_m, sin^2(pi/2 (s - start_m) / width_m) inside, 1 beyond; shown = (1 - w) fft + w baked.
struct DeepWaterBlendingRecord {
  std::string side;                 ///< "west", "east", "south" or "north": where the waves come from
  std::string axis;                 ///< "x" (west/east) or "y" (south/north)
  double source_line_m = 0.0;       ///< from the grid's south-west corner, along `axis`
  double start_m = 0.0, width_m = 0.0;
  double predicted_relative_rms_start = 0.0, predicted_relative_rms_end = 0.0;
  bool seamless = true;
  double seamless_relative_rms = 0.0;  ///< the bar `seamless` was judged against
};

/// How the field's frame and time relate to the bake's.
struct DeepWaterCouplingRecord {
  double origin_x_m = 0.0, origin_y_m = 0.0;  ///< the field's x = 0, y = 0: the grid's south-west corner
  bool drives_wave_maker = false;
  std::optional<DeepWaterMakerRecord> wave_maker;
  std::optional<DeepWaterBlendingRecord> blending;
};

/// The optional baked tile set (one cascade over one loop, a sequence of its own).
struct DeepWaterTileSetRecord {
  std::string folder;
  int cascade = 0;
  int frames = 0;
  double frame_interval_s = 0.0;
  std::uint64_t bytes = 0;
};

/// The manifest's `deep_water` section.
struct DeepWaterSection {
  /// The spectrum's own description (ocean's WavenumberSpectrum::to_json: "name" and its
  /// parameters), recorded for people and tools; the runtime synthesises from the coefficients.
  nlohmann::json spectrum;
  double mean_direction_rad = 0.0;
  double still_water_depth_m = 0.0;     ///< <= 0: deep water
  double loop_period_s = 0.0;           ///< 0 = the field does not loop
  double choppiness = 1.0;              ///< lambda
  std::uint64_t seed = 0;
  double significant_wave_height_m = 0.0;           ///< of the cascades
  double spectrum_significant_wave_height_m = 0.0;  ///< of the whole spectrum
  double unresolved_slope_variance = 0.0;           ///< beyond the last cascade (lighting roughness)
  double foam_breaking_jacobian = 0.0;              ///< J_b of the foam (ocean/deep_water.hpp)
  std::vector<DeepWaterCascadeRecord> cascades;
  std::optional<DeepWaterCouplingRecord> coupling;  ///< only in a harbour bake's manifest
  std::optional<DeepWaterTileSetRecord> tile_set;
  std::optional<int> tile_set_cascade;              ///< only in the tile set's own manifest
};

nlohmann::json deep_water_section_to_json(const DeepWaterSection& section);
/// Parses and checks the section; every problem is a nearshore::Error naming `source`, the key and
/// the fix. Never crashes on malformed input (the manifest reader is fuzzed).
DeepWaterSection parse_deep_water_section(const nlohmann::json& json, const std::string& source);

/// One deep_water_cascade_<i>.bin: N x N records in FFT order (row = ky index, column = kx index,
/// indices above N/2 negative). Header: 8-byte magic "NSDWCOEF", uint32 version 1, uint32 N, float64
/// L, float64 T_loop; then N*N records {float32 a, float32 phi, float32 w, int32 harmonic},
/// little-endian.
struct DeepWaterCoefficients {
  int grid_size = 0;           ///< N
  double tile_length_m = 0.0;  ///< L
  double loop_period_s = 0.0;  ///< T_loop, 0 = none
  std::vector<float> amplitude_m, phase_rad, angular_frequency_rad_s;
  std::vector<std::int32_t> harmonic;  ///< w = harmonic 2 pi / T_loop when looping, else -1
};
/// The file name of cascade `index`: "deep_water_cascade_<index>.bin".
std::string deep_water_coefficients_file_name(int index);
/// Writes the file atomically into `folder` and returns its manifest entry (size and XXH64).
FileEntry write_deep_water_coefficients(const std::filesystem::path& folder, int index,
                                        const DeepWaterCoefficients& coefficients);
/// Reads a coefficient file. Throws nearshore::Error naming the file for a missing file, another
/// magic or version, or a size that does not match N.
DeepWaterCoefficients read_deep_water_coefficients(const std::filesystem::path& file);

}  // namespace nearshore::sequence
